#ifndef vimlop_PipelineFlags_h
#define vimlop_PipelineFlags_h

#include <vimlop/Pipeline/VideoRegistrationPipeline.h>

namespace CLI
{
class App;
}

namespace vimlop
{

/**
 * @brief Adds the registration flags of the main job (noise, outliers, scale
 * bound, iterations, threads, multi-start, canonical spacing, failure
 * threshold) to `command`, stored into `options`, which must outlive the
 * parse. The defaults shown are those `options` holds: the pipeline's.
 */
void addPipelineOptions(CLI::App& command, VideoRegistrationPipeline::Options& options);

} // namespace vimlop

#endif
