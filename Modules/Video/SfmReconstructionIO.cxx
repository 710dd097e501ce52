#include <vimlop/Video/SfmReconstructionIO.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <limits>

namespace vimlop
{

namespace
{

using nlohmann::json;

json intrinsicsJson(const PinholeCamera& k)
{
  json j = { { "fx", k.fx }, { "fy", k.fy }, { "cx", k.cx }, { "cy", k.cy }, { "width", k.widthPx },
    { "height", k.heightPx } };
  std::vector<double> d(k.distortion.data(), k.distortion.data() + k.distortion.size());
  j["distortion"] = d;
  // Only the fisheye is named (as in IntrinsicsIO), so that files of the default model stay as they
  // were.
  if (k.lensModel == LensModel::Fisheye)
  {
    j["distortion_model"] = "fisheye";
  }
  return j;
}

/// An int from JSON: a whole number in int's range (a float such as 1e300
/// cast to int would be undefined behaviour, not an error).
int intFrom(const json& j, const char* what)
{
  const double v = j.is_number() ? j.get<double>() : 0.5;
  if (!j.is_number() || v != std::floor(v) || v < std::numeric_limits<int>::min() ||
    v > std::numeric_limits<int>::max())
  {
    throw Error(std::string("expected a whole number for ") + what);
  }
  return static_cast<int>(v);
}

PinholeCamera intrinsicsFrom(const json& j)
{
  PinholeCamera k;
  k.fx = j.at("fx").get<double>();
  k.fy = j.at("fy").get<double>();
  k.cx = j.at("cx").get<double>();
  k.cy = j.at("cy").get<double>();
  k.widthPx = intFrom(j.at("width"), "width");
  k.heightPx = intFrom(j.at("height"), "height");
  const std::vector<double> d = j.value("distortion", std::vector<double>());
  k.distortion = Eigen::Map<const Eigen::VectorXd>(d.data(), static_cast<Eigen::Index>(d.size()));
  const std::string model = j.value("distortion_model", std::string("plumb_bob"));
  if (model != "plumb_bob" && model != "fisheye")
  {
    throw Error("unknown distortion_model '" + model + "' (expected plumb_bob or fisheye)");
  }
  k.lensModel = model == "fisheye" ? LensModel::Fisheye : LensModel::RadialTangential;
  return k;
}

template <int N>
Eigen::Matrix<double, N, 1> vectorFrom(const json& j)
{
  if (!j.is_array() || j.size() != N)
  {
    throw Error("expected an array of " + std::to_string(N) + " numbers");
  }
  Eigen::Matrix<double, N, 1> v;
  for (int i = 0; i < N; ++i)
  {
    v[i] = j[static_cast<size_t>(i)].get<double>();
  }
  return v;
}

} // namespace

void writeSfmReconstruction(const SfmReconstruction& r, const std::string& path)
{
  json frames = json::array();
  for (const SfmReconstruction::Frame& f : r.frames)
  {
    std::vector<double> rotation;
    for (int row = 0; row < 3; ++row)
    {
      for (int col = 0; col < 3; ++col)
      {
        rotation.push_back(f.cameraToSfm.rotation(row, col));
      }
    }
    frames.push_back({ { "name", f.name }, { "registered", f.registered },
      { "intrinsics", intrinsicsJson(f.intrinsics) }, { "rotation", rotation },
      { "centre",
        { f.cameraToSfm.centre.x(), f.cameraToSfm.centre.y(), f.cameraToSfm.centre.z() } } });
  }
  json points = json::array();
  for (const SfmReconstruction::Point& p : r.points)
  {
    json observations = json::array();
    for (const SfmReconstruction::Observation& o : p.observations)
    {
      observations.push_back({ o.frame, o.pixel.x(), o.pixel.y() });
    }
    const Eigen::Matrix3d& c = p.covariance;
    points.push_back({ { "position", { p.position.x(), p.position.y(), p.position.z() } },
      { "covariance", { c(0, 0), c(0, 1), c(0, 2), c(1, 1), c(1, 2), c(2, 2) } },
      { "colour", { p.colour.x(), p.colour.y(), p.colour.z() } },
      { "error_px", p.reprojectionErrorPx }, { "observations", observations } });
  }
  const json document = { { "format", "vimlop-sfm" }, { "version", 1 }, { "source", r.source },
    { "rms_reprojection_error_px", r.rmsReprojectionErrorPx() },
    { "tracker_scale_mm_per_unit", r.trackerScale }, { "frames", frames }, { "points", points } };

  writeFileAtomically(path, document.dump(1) + "\n");
}

SfmReconstruction readSfmReconstruction(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throwFileError(path, "no such file or not readable");
  }
  json document;
  try
  {
    document = json::parse(in);
  }
  catch (const json::exception&)
  {
    throwFileError(path, "not a JSON file");
  }
  // value() would throw for a "format" that is no string (found by fuzzing).
  const auto format = document.is_object() ? document.find("format") : document.end();
  if (format == document.end() || !format->is_string() || *format != "vimlop-sfm")
  {
    throwFileError(path, "not a VIMLOP SfM file (no \"format\": \"vimlop-sfm\")");
  }
  SfmReconstruction r;
  try
  {
    r.source = document.value("source", std::string("builtin"));
    r.trackerScale = document.value("tracker_scale_mm_per_unit", 0.0);
    for (const json& f : document.at("frames"))
    {
      SfmReconstruction::Frame frame;
      frame.name = f.at("name").get<std::string>();
      frame.registered = f.at("registered").get<bool>();
      frame.intrinsics = intrinsicsFrom(f.at("intrinsics"));
      const Eigen::Matrix<double, 9, 1> rotation = vectorFrom<9>(f.at("rotation"));
      for (int row = 0; row < 3; ++row)
      {
        for (int col = 0; col < 3; ++col)
        {
          frame.cameraToSfm.rotation(row, col) = rotation[3 * row + col];
        }
      }
      frame.cameraToSfm.centre = vectorFrom<3>(f.at("centre"));
      r.frames.push_back(frame);
    }
    for (const json& p : document.at("points"))
    {
      SfmReconstruction::Point point;
      point.position = vectorFrom<3>(p.at("position"));
      const Eigen::Matrix<double, 6, 1> c = vectorFrom<6>(p.at("covariance"));
      point.covariance << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
      if (p.contains("colour"))
      {
        const json& colour = p.at("colour");
        if (!colour.is_array() || colour.size() != 3)
        {
          throw Error("expected an array of 3 numbers");
        }
        for (int a = 0; a < 3; ++a)
        {
          point.colour[a] = intFrom(colour[static_cast<size_t>(a)], "a colour");
        }
      }
      point.reprojectionErrorPx = p.value("error_px", 0.0);
      for (const json& o : p.at("observations"))
      {
        const Eigen::Vector3d v = vectorFrom<3>(o);
        point.observations.push_back({ intFrom(o[0], "a frame index"), v.tail<2>() });
      }
      r.points.push_back(std::move(point));
    }
  }
  catch (const json::exception& e)
  {
    throwFileError(path, std::string("malformed SfM file (") + e.what() + ")");
  }
  catch (const Error& e)
  {
    throwFileError(path, std::string("malformed SfM file (") + e.what() + ")");
  }
  try
  {
    r.validate();
  }
  catch (const Error& e)
  {
    throwFileError(path, std::string(e.what()));
  }
  return r;
}

} // namespace vimlop
