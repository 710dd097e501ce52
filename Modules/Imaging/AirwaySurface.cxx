#include <vimlop/Imaging/AirwaySurface.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/OrientNormalsIntoAir.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Imaging/PolyDataConversion.h>

#include <vtkCellArray.h>
#include <vtkCleanPolyData.h>
#include <vtkCommand.h>
#include <vtkDecimatePro.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataAlgorithm.h>
#include <vtkPolyDataConnectivityFilter.h>
#include <vtkPolyDataNormals.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace vimlop
{

namespace
{

/// Forwards a VTK filter's progress into the part [begin, end] of the overall progress.
class ProgressForwarder : public vtkCommand
{
public:
  static ProgressForwarder* New() { return new ProgressForwarder; }
  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    const double filterProgress = *static_cast<double*>(callData);
    reportProgress(
      *this->Progress, this->Begin + (this->End - this->Begin) * filterProgress, this->Step);
  }
  const ProgressCallback* Progress = nullptr;
  double Begin = 0.0;
  double End = 1.0;
  std::string Step;
};

void runFilter(vtkAlgorithm* filter, const ProgressCallback& progress, double begin, double end,
  const std::string& step)
{
  if (progress)
  {
    vtkNew<ProgressForwarder> forwarder;
    forwarder->Progress = &progress;
    forwarder->Begin = begin;
    forwarder->End = end;
    forwarder->Step = step;
    filter->AddObserver(vtkCommand::ProgressEvent, forwarder);
    filter->Update();
    filter->RemoveObservers(vtkCommand::ProgressEvent);
  }
  else
  {
    filter->Update();
  }
}

/// The triangles without pairs that share their three corners: decimation
/// can flatten a thin tube into two coincident faces of opposite winding, a
/// zero-volume pocket whose edges count as non-manifold. Both faces go, which
/// keeps the surface closed.
vtkSmartPointer<vtkPolyData> withoutCoincidentPairs(vtkPolyData* surface, int& removed)
{
  std::map<std::array<vtkIdType, 3>, std::vector<vtkIdType>> byCorners;
  vtkCellArray* polys = surface->GetPolys();
  vtkIdType count = 0;
  const vtkIdType* ids = nullptr;
  vtkIdType cell = 0;
  for (polys->InitTraversal(); polys->GetNextCell(count, ids); ++cell)
  {
    if (count == 3)
    {
      std::array<vtkIdType, 3> key{ ids[0], ids[1], ids[2] };
      std::sort(key.begin(), key.end());
      byCorners[key].push_back(cell);
    }
  }
  std::vector<bool> drop(static_cast<std::size_t>(cell), false);
  removed = 0;
  for (const auto& [corners, cells] : byCorners)
  {
    if (cells.size() >= 2)
    {
      // Drop an even number, so that an edge keeps an even face count.
      const std::size_t pairs = cells.size() / 2;
      for (std::size_t c = 0; c < 2 * pairs; ++c)
      {
        drop[static_cast<std::size_t>(cells[c])] = true;
        ++removed;
      }
    }
  }
  if (removed == 0)
  {
    return surface;
  }
  vtkNew<vtkCellArray> kept;
  cell = 0;
  for (polys->InitTraversal(); polys->GetNextCell(count, ids); ++cell)
  {
    if (!drop[static_cast<std::size_t>(cell)])
    {
      kept->InsertNextCell(count, ids);
    }
  }
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->SetPoints(surface->GetPoints());
  result->SetPolys(kept);
  return result;
}

} // namespace

AirwaySurface AirwaySurface::compute(
  const CTVolume& label, const AirwaySurfaceOptions& options, const ProgressCallback& progress)
{
  if (label.dims[0] < 2 || label.dims[1] < 2 || label.dims[2] < 2 ||
    label.intensities.size() != label.numberOfVoxels())
  {
    throw Error("the airway label is not a consistent 3-D volume");
  }
  if (options.targetTriangles < 0 || options.targetTriangles == 1 || options.targetTriangles == 2 ||
    options.targetTriangles == 3)
  {
    throw Error("the target triangle count must be 0 (no decimation) or at least 4");
  }
  if (options.smoothingIterations < 0 ||
    !(options.smoothingPassBand > 0.0 && options.smoothingPassBand <= 2.0))
  {
    throw Error("smoothing needs a non-negative number of iterations and a pass band in (0, 2]");
  }

  // 1. The label's bounding box, padded with one voxel of background.
  std::array<int, 3> lo{ label.dims[0], label.dims[1], label.dims[2] };
  std::array<int, 3> hi{ -1, -1, -1 };
  std::size_t i = 0;
  for (int k = 0; k < label.dims[2]; ++k)
  {
    for (int j = 0; j < label.dims[1]; ++j)
    {
      for (int x = 0; x < label.dims[0]; ++x, ++i)
      {
        if (label.intensities[i] != 0.0f)
        {
          lo = { std::min(lo[0], x), std::min(lo[1], j), std::min(lo[2], k) };
          hi = { std::max(hi[0], x), std::max(hi[1], j), std::max(hi[2], k) };
        }
      }
    }
  }
  if (hi[0] < 0)
  {
    throw Error("the airway label is empty");
  }
  const std::array<int, 3> dims{ hi[0] - lo[0] + 3, hi[1] - lo[1] + 3, hi[2] - lo[2] + 3 };
  vtkNew<vtkImageData> image;
  image->SetDimensions(dims.data());
  image->SetSpacing(label.spacingMm.data());
  image->SetOrigin(0.0, 0.0, 0.0);
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfTuples(static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2]);
  values->FillValue(0.0f);
  for (int k = lo[2]; k <= hi[2]; ++k)
  {
    for (int j = lo[1]; j <= hi[1]; ++j)
    {
      for (int x = lo[0]; x <= hi[0]; ++x)
      {
        const std::size_t from = static_cast<std::size_t>(x) +
          static_cast<std::size_t>(label.dims[0]) *
            (j + static_cast<std::size_t>(label.dims[1]) * k);
        const vtkIdType to = (x - lo[0] + 1) +
          static_cast<vtkIdType>(dims[0]) *
            ((j - lo[1] + 1) + static_cast<vtkIdType>(dims[1]) * (k - lo[2] + 1));
        values->SetValue(to, label.intensities[from] != 0.0f ? 1.0f : 0.0f);
      }
    }
  }
  image->GetPointData()->SetScalars(values);

  vtkNew<vtkFlyingEdges3D> isoSurface;
  isoSurface->SetInputData(image);
  isoSurface->SetValue(0, 0.5);
  isoSurface->ComputeNormalsOff();
  isoSurface->ComputeGradientsOff();
  isoSurface->ComputeScalarsOff();
  runFilter(isoSurface, progress, 0.0, 0.15, "iso-surface");
  vtkSmartPointer<vtkPolyData> surface = isoSurface->GetOutput();

  // 2. Decimation, before smoothing: on the staircase of voxel faces the
  // topology-preserving decimation removes flat runs first and leaves fewer
  // folded or pinched triangles than on a smoothed surface.
  const vtkIdType isoTriangles = surface->GetNumberOfPolys();
  const int isoSurfaceTriangles = static_cast<int>(isoTriangles);
  if (options.targetTriangles > 0 && isoTriangles > options.targetTriangles)
  {
    vtkNew<vtkDecimatePro> decimate;
    decimate->SetInputData(surface);
    decimate->SetTargetReduction(
      1.0 - static_cast<double>(options.targetTriangles) / static_cast<double>(isoTriangles));
    // Keep the surface closed and manifold: no splitting, no hole opening.
    decimate->PreserveTopologyOn();
    decimate->SplittingOff();
    decimate->BoundaryVertexDeletionOff();
    decimate->SetFeatureAngle(45.0);
    runFilter(decimate, progress, 0.15, 0.65, "decimation");
    surface = decimate->GetOutput();
  }

  // 3. Smoothing.
  if (options.smoothingIterations > 0)
  {
    vtkNew<vtkWindowedSincPolyDataFilter> smoother;
    smoother->SetInputData(surface);
    smoother->SetNumberOfIterations(options.smoothingIterations);
    smoother->SetPassBand(options.smoothingPassBand);
    smoother->BoundarySmoothingOff();
    smoother->FeatureEdgeSmoothingOff();
    smoother->NonManifoldSmoothingOn();
    // Normalised coordinates keep the filter's response independent of the size.
    smoother->NormalizeCoordinatesOn();
    runFilter(smoother, progress, 0.65, 0.85, "smoothing");
    surface = smoother->GetOutput();
  }

  // 4. The largest piece (and no zero-volume pockets).
  int coincident = 0;
  surface = withoutCoincidentPairs(surface, coincident);
  vtkNew<vtkPolyDataConnectivityFilter> pieces;
  pieces->SetInputData(surface);
  pieces->SetExtractionModeToAllRegions();
  runFilter(pieces, progress, 0.85, 0.9, "connectivity");
  AirwaySurface result;
  result.isoSurfaceTriangles = isoSurfaceTriangles;
  result.targetTriangles = options.targetTriangles;
  result.droppedPieces = std::max(0, pieces->GetNumberOfExtractedRegions() - 1);
  {
    vtkIdTypeArray* sizes = pieces->GetRegionSizes();
    vtkIdType total = 0;
    vtkIdType largest = 0;
    for (vtkIdType r = 0; r < sizes->GetNumberOfTuples(); ++r)
    {
      total += sizes->GetValue(r);
      largest = std::max(largest, sizes->GetValue(r));
    }
    result.droppedTriangleFraction =
      total > 0 ? static_cast<double>(total - largest) / static_cast<double>(total) : 0.0;
  }
  vtkNew<vtkPolyDataConnectivityFilter> largest;
  largest->SetInputData(surface);
  largest->SetExtractionModeToLargestRegion();
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(largest->GetOutputPort());
  clean->PointMergingOff(); // only drop the points no triangle uses
  runFilter(clean, progress, 0.9, 0.93, "connectivity");
  surface = clean->GetOutput();

  // 5. To the CT frame: index-times-spacing coordinates of the padded box
  // start at the label's voxel lo - 1.
  const std::array<double, 3> boxOrigin =
    label.indexToPhysical({ lo[0] - 1.0, lo[1] - 1.0, lo[2] - 1.0 });
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(surface->GetNumberOfPoints());
  for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
  {
    const double* local = surface->GetPoint(p);
    std::array<double, 3> world = boxOrigin;
    for (int row = 0; row < 3; ++row)
    {
      for (int col = 0; col < 3; ++col)
      {
        world[row] += label.direction[3 * row + col] * local[col];
      }
    }
    points->SetPoint(p, world.data());
  }
  vtkNew<vtkPolyData> mapped;
  mapped->SetPoints(points);
  mapped->SetPolys(surface->GetPolys());

  // 6. Normals into the air. Make the winding consistent first (flying edges
  // and the filters after it keep it, but decimation may fold a triangle),
  // then orient by the loaders' rule (orientIntoAir()).
  vtkNew<vtkPolyDataNormals> consistent;
  consistent->SetInputData(mapped);
  consistent->ConsistencyOn();
  consistent->AutoOrientNormalsOff();
  consistent->SplittingOff();
  consistent->ComputePointNormalsOff();
  consistent->ComputeCellNormalsOff();
  runFilter(consistent, progress, 0.93, 0.96, "orientation");
  const TriangleMesh oriented = orientIntoAir(toTriangleMesh(consistent->GetOutput()), label);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(toPolyData(oriented));
  normals->ConsistencyOff();
  normals->AutoOrientNormalsOff();
  normals->SplittingOff();
  normals->ComputePointNormalsOn();
  normals->ComputeCellNormalsOn();
  runFilter(normals, progress, 0.96, 0.99, "normals");
  result.surface = normals->GetOutput();

  // The report, of the mesh as a loader reads it.
  result.triangles = oriented.numberOfFaces();
  result.vertices = oriented.numberOfVertices();
  result.boundaryEdges = oriented.numberOfBoundaryEdges();
  result.nonManifoldEdges = oriented.numberOfNonManifoldEdges();
  result.areaMm2 = oriented.totalArea();
  // Normals into the enclosed air make the signed volume negative.
  result.enclosedVolumeMm3 = -oriented.signedVolume();
  reportProgress(progress, 1.0, "done");
  return result;
}

std::string AirwaySurface::summaryText() const
{
  return formatText("surface %d triangles, %d vertices, encloses %.1f cm^3, area %.1f cm^2, %d "
                    "open edges, %d non-manifold edges",
    this->triangles, this->vertices, this->enclosedVolumeMm3 / 1000.0, this->areaMm2 / 100.0,
    this->boundaryEdges, this->nonManifoldEdges);
}

std::vector<std::string> AirwaySurface::warnings() const
{
  std::vector<std::string> warnings;
  if (this->boundaryEdges > 0 || this->nonManifoldEdges > 0)
  {
    warnings.push_back(
      formatText("the surface has %d open boundary edges and %d non-manifold edges",
        this->boundaryEdges, this->nonManifoldEdges));
  }
  if (this->droppedTriangleFraction > 0.01)
  {
    warnings.push_back(formatText("%d disconnected pieces (%.1f%% of the surface) were dropped",
      this->droppedPieces, 100.0 * this->droppedTriangleFraction));
  }
  if (this->targetTriangles > this->isoSurfaceTriangles)
  {
    // Decimation cannot add triangles, and subdividing would add none of the
    // anatomy's detail: the voxels bound it.
    warnings.push_back(formatText(
      "asked for %d triangles, but the iso-surface of the airway has only %d: it is kept "
      "undecimated (a finer surface needs a CT with smaller voxels)",
      this->targetTriangles, this->isoSurfaceTriangles));
  }
  return warnings;
}

TriangleMesh AirwaySurface::orientIntoAir(const TriangleMesh& mesh, const CTVolume& label)
{
  if (mesh.numberOfBoundaryEdges() == 0)
  {
    return orientNormalsIntoAir(mesh);
  }
  // An open surface encloses nothing, and orientNormalsIntoAir() keeps its
  // faces as they are, so their order must be right here. The label knows
  // the air side: a face's normal should lead from tissue into label voxels.
  // Probing half the smallest voxel either side of the centroid reaches the
  // voxel centres on both sides of the iso-surface (it lies half a voxel
  // from them), and the vote over all faces outweighs the odd folded one.
  const double step = 0.5 * *std::min_element(label.spacingMm.begin(), label.spacingMm.end());
  const auto inLabel = [&label](const Eigen::Vector3d& p)
  {
    const std::array<double, 3> index = label.physicalToIndex({ p.x(), p.y(), p.z() });
    std::array<long long, 3> voxel{};
    for (int a = 0; a < 3; ++a)
    {
      voxel[a] = std::llround(index[a]);
      if (voxel[a] < 0 || voxel[a] >= label.dims[a])
      {
        return false;
      }
    }
    const std::size_t at = static_cast<std::size_t>(voxel[0]) +
      static_cast<std::size_t>(label.dims[0]) *
        (static_cast<std::size_t>(voxel[1]) +
          static_cast<std::size_t>(label.dims[1]) * static_cast<std::size_t>(voxel[2]));
    return label.intensities[at] != 0.0f;
  };
  long long intoAir = 0;
  long long outOfAir = 0;
  for (int f = 0; f < mesh.numberOfFaces(); ++f)
  {
    const Eigen::Vector3d centre = mesh.faceCentroid(f);
    const Eigen::Vector3d& n = mesh.faceNormals()[f];
    const bool front = inLabel(centre + step * n);
    const bool back = inLabel(centre - step * n);
    intoAir += front && !back ? 1 : 0;
    outOfAir += back && !front ? 1 : 0;
  }
  return outOfAir > intoAir ? mesh.flipped() : mesh;
}

} // namespace vimlop
