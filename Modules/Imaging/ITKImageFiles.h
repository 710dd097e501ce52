#ifndef vimlop_ITKImageIOFactories_h
#define vimlop_ITKImageIOFactories_h

// Private to the Imaging module (not installed).

namespace vimlop::detail
{

/// Registers ITK's NIfTI, NRRD, MetaImage and GDCM image IO factories, once
/// (we do not rely on ITK's generated factory lists). Thread-safe.
void registerImageIOs();

} // namespace vimlop::detail

#endif
