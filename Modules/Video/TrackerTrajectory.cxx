#include <vimlop/Video/TrackerTrajectory.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Core/TransformSequenceFile.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

namespace vimlop
{

namespace
{

std::vector<std::string> splitCsv(const std::string& line)
{
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ','))
  {
    fields.push_back(trimmed(field));
  }
  if (!line.empty() && line.back() == ',')
  {
    fields.emplace_back();
  }
  return fields;
}

bool parseNumber(const std::string& text, double& value)
{
  if (text.empty())
  {
    return false;
  }
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(value);
}

/// A tracker glitch (metal nearby, a loose sensor) is a sample far from the
/// samples around it. The tip of a hand-held endoscope moves at most about
/// 100 mm/s, so within a window of samples every clean position lies within
/// that speed times the window's span of the others, and of their median;
/// the 10 mm floor covers tracker noise. A glitch of a metre otherwise
/// made the scale 14 times too large.
constexpr int GlitchWindowHalfWidth = 3;
constexpr double GlitchMaxSpeedMmPerS = 100.0;
constexpr double GlitchFloorMm = 10.0;

/// Indices of samples (sorted by time) far from the median of their window.
std::vector<size_t> findGlitches(const std::vector<TrackerTrajectory::Sample>& samples)
{
  std::vector<size_t> glitches;
  const size_t n = samples.size();
  std::vector<double> values;
  for (size_t i = 0; i < n; ++i)
  {
    const size_t first = i >= GlitchWindowHalfWidth ? i - GlitchWindowHalfWidth : 0;
    const size_t last = std::min(n - 1, i + GlitchWindowHalfWidth);
    if (last - first < 3)
    {
      continue; // too few samples for a median to outvote one
    }
    Eigen::Vector3d median;
    for (int axis = 0; axis < 3; ++axis)
    {
      values.clear();
      for (size_t j = first; j <= last; ++j)
      {
        values.push_back(samples[j].positionMm[axis]);
      }
      std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
      median[axis] = values[values.size() / 2];
    }
    const double spanS = samples[last].timeS - samples[first].timeS;
    const double limitMm = GlitchFloorMm + std::sqrt(3.0) * GlitchMaxSpeedMmPerS * spanS;
    if ((samples[i].positionMm - median).norm() > limitMm)
    {
      glitches.push_back(i);
    }
  }
  return glitches;
}

} // namespace

TrackerTrajectory::TrackerTrajectory(
  std::vector<Sample> samples, std::vector<std::string>* warnings)
{
  for (const Sample& s : samples)
  {
    if (!std::isfinite(s.timeS) || !s.positionMm.allFinite())
    {
      throw Error("tracker trajectory: a sample has a non-finite time or position");
    }
  }
  std::stable_sort(samples.begin(), samples.end(),
    [](const Sample& a, const Sample& b) { return a.timeS < b.timeS; });
  int duplicates = 0;
  for (const Sample& s : samples)
  {
    if (!this->Samples.empty() && s.timeS <= this->Samples.back().timeS)
    {
      ++duplicates;
      continue;
    }
    this->Samples.push_back(s);
  }
  if (duplicates > 0 && warnings)
  {
    warnings->push_back(
      "dropped " + std::to_string(duplicates) + " tracker sample(s) with a timestamp already seen");
  }
  const std::vector<size_t> glitches = findGlitches(this->Samples);
  if (!glitches.empty())
  {
    std::ostringstream message;
    message << "dropped " << glitches.size()
            << " tracker sample(s) far from the samples around them, a glitch of the tracker? (at ";
    for (size_t k = 0; k < std::min<size_t>(glitches.size(), 3); ++k)
    {
      message << (k ? ", " : "") << std::fixed << std::setprecision(3)
              << this->Samples[glitches[k]].timeS << " s";
    }
    message << (glitches.size() > 3 ? ", ...)" : ")");
    for (auto g = glitches.rbegin(); g != glitches.rend(); ++g)
    {
      this->Samples.erase(this->Samples.begin() + static_cast<std::ptrdiff_t>(*g));
    }
    if (warnings)
    {
      warnings->push_back(message.str());
    }
  }
  if (this->Samples.size() < 2)
  {
    throw Error("tracker trajectory: needs at least 2 samples with distinct times, got " +
      std::to_string(this->Samples.size()));
  }
}

TrackerTrajectory TrackerTrajectory::readTrackedSequence(
  const std::string& path, const std::string& transformName, std::vector<std::string>* warnings)
{
  std::vector<Sample> samples;
  for (const TimedTransform& item : readTransformSequenceFile(path, transformName))
  {
    samples.push_back({ item.timeS, item.matrix.topRightCorner<3, 1>(),
      Eigen::Matrix3d(item.matrix.topLeftCorner<3, 3>()) });
  }
  if (samples.size() < 2)
  {
    throwFileError(path,
      "the transform '" + transformName + "' has " + std::to_string(samples.size()) +
        " usable frame; a tracker needs at least 2");
  }
  return TrackerTrajectory(std::move(samples), warnings);
}

TrackerTrajectory TrackerTrajectory::readCsv(
  const std::string& path, std::vector<std::string>* warnings)
{
  std::ifstream in(path);
  if (!in)
  {
    throwFileError(path, "no such file or not readable");
  }
  std::string line;
  int lineNumber = 0;
  std::vector<std::string> header;
  while (std::getline(in, line))
  {
    ++lineNumber;
    const std::string t = trimmed(line);
    if (!t.empty() && t[0] != '#')
    {
      header = splitCsv(t);
      break;
    }
  }
  if (header.empty())
  {
    throwFileError(path, "the file is empty (expected a header: time_s,x_mm,y_mm,z_mm)");
  }
  const std::map<std::string, int> columnOf = [&]
  {
    std::map<std::string, int> m;
    for (size_t i = 0; i < header.size(); ++i)
    {
      m[lowerCase(header[i])] = static_cast<int>(i);
    }
    return m;
  }();
  auto find = [&](std::initializer_list<const char*> names, const char* what)
  {
    for (const char* name : names)
    {
      const auto found = columnOf.find(name);
      if (found != columnOf.end())
      {
        return found->second;
      }
    }
    throw Error(
      "'" + path + "': no column '" + what + "' in the header (expected time_s,x_mm,y_mm,z_mm)");
  };
  const int columns[4] = { find({ "time_s", "t", "time", "timestamp" }, "time_s"),
    find({ "x_mm", "x" }, "x_mm"), find({ "y_mm", "y" }, "y_mm"), find({ "z_mm", "z" }, "z_mm") };
  // A 6-DOF sensor's rotation, as a unit quaternion: all four columns or none.
  const char* const quaternionNames[4] = { "qw", "qx", "qy", "qz" };
  int quaternionColumns[4];
  int quaternionsFound = 0;
  for (int c = 0; c < 4; ++c)
  {
    const auto found = columnOf.find(quaternionNames[c]);
    quaternionColumns[c] = found == columnOf.end() ? -1 : found->second;
    quaternionsFound += found == columnOf.end() ? 0 : 1;
  }
  if (quaternionsFound > 0 && quaternionsFound < 4)
  {
    throwFileError(path,
      "the header has only " + std::to_string(quaternionsFound) +
        " of the rotation's columns qw,qx,qy,qz (all four or none)");
  }
  const bool rotations = quaternionsFound == 4;

  std::vector<Sample> samples;
  std::vector<int> malformed;
  while (std::getline(in, line))
  {
    ++lineNumber;
    const std::string t = trimmed(line);
    if (t.empty() || t[0] == '#')
    {
      continue;
    }
    const std::vector<std::string> fields = splitCsv(t);
    const auto read = [&](const int* at, double* values)
    {
      bool ok = true;
      for (int c = 0; c < 4 && ok; ++c)
      {
        ok = at[c] < static_cast<int>(fields.size()) &&
          parseNumber(fields[static_cast<size_t>(at[c])], values[c]);
      }
      return ok;
    };
    double values[4];
    double q[4];
    // A quaternion a tracker wrote with a few digits is a little off unit
    // length; one far from it is no rotation.
    const bool ok = read(columns, values) &&
      (!rotations ||
        (read(quaternionColumns, q) &&
          std::abs(Eigen::Vector4d(q[0], q[1], q[2], q[3]).norm() - 1.0) <= 0.01));
    if (!ok)
    {
      malformed.push_back(lineNumber);
      continue;
    }
    std::optional<Eigen::Matrix3d> rotation;
    if (rotations)
    {
      rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
    }
    samples.push_back({ values[0], Eigen::Vector3d(values[1], values[2], values[3]), rotation });
  }
  if (!malformed.empty() && warnings)
  {
    std::string lines;
    for (size_t i = 0; i < malformed.size() && i < 5; ++i)
    {
      lines += (i ? ", " : "") + std::to_string(malformed[i]);
    }
    if (malformed.size() > 5)
    {
      lines += ", ...";
    }
    warnings->push_back("'" + path + "': dropped " + std::to_string(malformed.size()) +
      " malformed row(s) (line " + lines + ")");
  }
  if (samples.size() < 2)
  {
    throwFileError(path,
      "too few tracker rows: " + std::to_string(samples.size()) + " usable, at least 2 needed");
  }
  try
  {
    return TrackerTrajectory(std::move(samples), warnings);
  }
  catch (const Error& e)
  {
    throwFileError(path, std::string(e.what()));
  }
}

bool TrackerTrajectory::hasRotations() const
{
  return std::all_of(this->Samples.begin(), this->Samples.end(),
    [](const Sample& s) { return s.rotation.has_value(); });
}

void TrackerTrajectory::writeCsv(const std::string& path) const
{
  std::ofstream out(path);
  // Every digit: a reader gets the very samples back (a rounded time stamp can move
  // a sample across the edge of the window that a position is fitted over).
  const bool rotations = this->hasRotations();
  out << (rotations ? "time_s,x_mm,y_mm,z_mm,qw,qx,qy,qz\n" : "time_s,x_mm,y_mm,z_mm\n")
      << std::setprecision(std::numeric_limits<double>::max_digits10);
  for (const Sample& s : this->Samples)
  {
    out << s.timeS << "," << s.positionMm.x() << "," << s.positionMm.y() << "," << s.positionMm.z();
    if (rotations)
    {
      const Eigen::Quaterniond q(*s.rotation);
      out << "," << q.w() << "," << q.x() << "," << q.y() << "," << q.z();
    }
    out << "\n";
  }
  if (!out)
  {
    throwFileError(path, "cannot write the file");
  }
}

std::optional<Eigen::Vector3d> TrackerTrajectory::positionAt(double timeS, double smoothingS) const
{
  if (this->Samples.empty() || timeS < this->startS() || timeS > this->endS())
  {
    return std::nullopt;
  }
  if (smoothingS <= 0.0)
  {
    const auto after = std::lower_bound(this->Samples.begin(), this->Samples.end(), timeS,
      [](const Sample& s, double t) { return s.timeS < t; });
    if (after == this->Samples.begin())
    {
      return after->positionMm;
    }
    const Sample& b = *after;
    const Sample& a = *(after - 1);
    const double w = (timeS - a.timeS) / (b.timeS - a.timeS);
    return Eigen::Vector3d((1.0 - w) * a.positionMm + w * b.positionMm);
  }
  // A local line fitted with Gaussian weights over +-3 sigma (local linear
  // regression): unlike a weighted mean it does not lag behind a moving tip
  // where the window is one-sided, at the ends of the recording.
  Eigen::Vector3d s0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d s1 = Eigen::Vector3d::Zero();
  double w0 = 0.0;
  double w1 = 0.0;
  double w2 = 0.0;
  const auto first = std::lower_bound(this->Samples.begin(), this->Samples.end(),
    timeS - 3.0 * smoothingS, [](const Sample& s, double t) { return s.timeS < t; });
  for (auto it = first; it != this->Samples.end() && it->timeS <= timeS + 3.0 * smoothingS; ++it)
  {
    const double dt = it->timeS - timeS;
    const double d = dt / smoothingS;
    const double w = std::exp(-0.5 * d * d);
    s0 += w * it->positionMm;
    s1 += w * dt * it->positionMm;
    w0 += w;
    w1 += w * dt;
    w2 += w * dt * dt;
  }
  const double determinant = w0 * w2 - w1 * w1;
  if (w0 <= 0.0 || determinant <= 1e-12 * w0 * w2)
  {
    return this->positionAt(timeS, 0.0);
  }
  // Intercept of the weighted line p(t) = a + b (t - timeS).
  return Eigen::Vector3d((w2 * s0 - w1 * s1) / determinant);
}

std::optional<Eigen::Matrix4d> TrackerTrajectory::poseAt(double timeS) const
{
  if (this->Samples.empty() || timeS < this->startS() || timeS > this->endS())
  {
    return std::nullopt;
  }
  const auto after = std::lower_bound(this->Samples.begin(), this->Samples.end(), timeS,
    [](const Sample& s, double t) { return s.timeS < t; });
  const Sample& b = *after;
  const Sample& a = after == this->Samples.begin() ? b : *(after - 1);
  if (!a.rotation || !b.rotation)
  {
    return std::nullopt;
  }
  const double w = b.timeS > a.timeS ? (timeS - a.timeS) / (b.timeS - a.timeS) : 0.0;
  // A tracker's matrix may carry rounding away from a rotation: the nearest
  // unit quaternions are interpolated.
  const Eigen::Quaterniond qa(*a.rotation);
  const Eigen::Quaterniond qb(*b.rotation);
  Eigen::Matrix4d pose = Eigen::Matrix4d::Identity();
  pose.topLeftCorner<3, 3>() = qa.normalized().slerp(w, qb.normalized()).toRotationMatrix();
  pose.topRightCorner<3, 1>() = (1.0 - w) * a.positionMm + w * b.positionMm;
  return pose;
}

} // namespace vimlop
