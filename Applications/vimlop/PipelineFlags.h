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
 * @brief Adds a flag for every setting of the main job to `command`, stored
 * into `options`, which must outlive the parse: one per row of
 * RegistrationOptionTable.h and VideoRegistrationOptionTable.h (with the
 * row's range as the check), Σ2d and the scale factors. The defaults shown
 * are those `options` holds: the pipeline's.
 */
void addPipelineOptions(CLI::App& command, VideoRegistrationOptions& options);

} // namespace vimlop

#endif
