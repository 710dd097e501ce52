#ifndef vimlop_ContourOverlay_h
#define vimlop_ContourOverlay_h

#include <vimlop/Core/ContourPoint.h>

#include "VIMLOPRenderingModule.h"

#include <vtkSmartPointer.h>

#include <vector>

class vtkImageData;

/**
 * @file ContourOverlay.h
 * @brief The report's contour pictures (the paper's Fig. 2): a video frame
 * with the model's occluding contours in green and the video contours in white.
 *
 * All images are RGB unsigned char VTK images (row 0 at the bottom); pixel
 * (u, v) of the OpenCV convention is at (u, heightPx - 1 - v).
 */

namespace vimlop
{

/**
 * @brief The overlay of one frame, `widthPx` x `heightPx` pixels.
 *
 * @param frame the frame's picture (RGB, the frame's size), or null for a
 *   dark grey background
 * @param modelContours mask of the model's contours (one component, non-zero
 *   on contour pixels, the frame's size, as vtkVIMLOPSilhouetteRenderer
 *   draws them), or null; drawn in green
 * @param videoContour the video contour points (pixels), drawn in white on
 *   top, each at its nearest pixel
 * @throws vimlop::Error if a picture's size is not the frame's.
 */
VIMLOPRENDERING_EXPORT vtkSmartPointer<vtkImageData> composeContourOverlay(int widthPx,
  int heightPx, vtkImageData* frame, vtkImageData* modelContours,
  const std::vector<ContourPoint>& videoContour);

/**
 * @brief Pictures of the same height side by side, left to right, with
 * `gapPx` columns of black between them.
 * @throws vimlop::Error for no pictures or pictures of different heights.
 */
VIMLOPRENDERING_EXPORT vtkSmartPointer<vtkImageData> placeSideBySide(
  const std::vector<vtkSmartPointer<vtkImageData>>& pictures, int gapPx);

} // namespace vimlop

#endif
