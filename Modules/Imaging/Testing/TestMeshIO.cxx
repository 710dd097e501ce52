#include "ErrorMessage.h"
#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkPolyData.h>

#include <filesystem>
#include <fstream>
#include <iterator>

using namespace vimlop;

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;

} // namespace

class MeshRoundTrip : public ::testing::TestWithParam<std::string>
{
};

TEST_P(MeshRoundTrip, KeepsVerticesFacesAndOrientation)
{
  const TriangleMesh sphere = fixtures::makeSphere(7.5, 2, { 1, 2, 3 });
  const std::string path = out + "/sphere" + GetParam();
  writePolyData(toPolyData(sphere), path);
  const TriangleMesh back = toTriangleMesh(readPolyData(path));
  ASSERT_EQ(back.numberOfFaces(), sphere.numberOfFaces());
  EXPECT_NEAR(back.totalArea(), sphere.totalArea(), 1e-3);
  // STL stores vertices per face and in float; compare geometry, not indices.
  for (int f = 0; f < sphere.numberOfFaces(); ++f)
  {
    ASSERT_LT((back.faceCentroid(f) - sphere.faceCentroid(f)).norm(), 1e-4);
    ASSERT_GT(back.faceNormals()[f].dot(sphere.faceNormals()[f]), 0.9999);
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, MeshRoundTrip, ::testing::Values(".vtp", ".vtk", ".stl", ".ply"),
  [](const auto& info) { return info.param.substr(1); });

TEST(MeshIO, ConversionTriangulatesPolygons)
{
  auto quad = toPolyData(fixtures::makeBox({ 0, 0, 0 }, { 1, 1, 1 }));
  EXPECT_EQ(toTriangleMesh(quad).numberOfFaces(), 12);
  vtkNew<vtkPolyData> empty;
  EXPECT_THROW(toTriangleMesh(empty), Error);
}

TEST(MeshIO, ConversionDropsTrianglesThatRepeatAPoint)
{
  // Decimation and point merging in other tools leave triangles such as
  // (a, a, b); they cover no surface and must not make the mesh unusable.
  auto box = toPolyData(fixtures::makeBox({ 0, 0, 0 }, { 1, 1, 1 }));
  const vtkIdType degenerate[3][3] = { { 0, 0, 1 }, { 2, 3, 3 }, { 4, 5, 4 } };
  for (const auto& ids : degenerate)
  {
    box->GetPolys()->InsertNextCell(3, ids);
  }
  ASSERT_EQ(box->GetNumberOfPolys(), 15);
  EXPECT_EQ(toTriangleMesh(box).numberOfFaces(), 12);
}

TEST(MeshIO, ErrorsNameTheFileAndTheProblem)
{
  auto message = [](const std::string& path)
  {
    try
    {
      readPolyData(path);
    }
    catch (const Error& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(out + "/none.vtp"), "'" + out + "/none.vtp': no such file");
  std::ofstream(out + "/garbage.vtp") << "<not vtk>";
  EXPECT_EQ(
    message(out + "/garbage.vtp"), "'" + out + "/garbage.vtp': not a VTK XML polydata file");
  std::ofstream(out + "/garbage.ply") << "nothing";
  EXPECT_EQ(message(out + "/garbage.ply"), "'" + out + "/garbage.ply': not a PLY file");
  std::ofstream(out + "/mesh.off") << "OFF";
  EXPECT_EQ(message(out + "/mesh.off"),
    "'" + out + "/mesh.off': unsupported mesh file type (expected .vtp, .vtk, .stl, .ply or .obj)");
  EXPECT_THROW(
    writePolyData(toPolyData(fixtures::makeBox({ 0, 0, 0 }, { 1, 1, 1 })), out + "/x.obj"), Error);
}

namespace
{

std::string readError(const std::string& path)
{
  return fixtures::errorMessageOf([&] { readPolyData(path); });
}

/// A PLY file of one triangle: the header, then `body` as given.
std::string writePly(const std::string& name, const std::string& format, const std::string& body,
  const std::string& faceList = "uchar int")
{
  const std::string path = out + "/" + name;
  std::ofstream(path, std::ios::binary)
    << "ply\nformat " << format << " 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    << "property float z\nelement face 1\nproperty list " << faceList
    << " vertex_indices\nend_header\n"
    << body;
  return path;
}

std::string floats(std::initializer_list<float> values)
{
  std::string bytes;
  for (float v : values)
  {
    bytes.append(reinterpret_cast<const char*>(&v), sizeof(v));
  }
  return bytes;
}

std::string face(std::uint8_t count, std::initializer_list<std::int32_t> ids)
{
  std::string bytes(1, static_cast<char>(count));
  for (std::int32_t id : ids)
  {
    bytes.append(reinterpret_cast<const char*>(&id), sizeof(id));
  }
  return bytes;
}

} // namespace

TEST(MeshIO, APlyFileIsReadByVIMLOPWhichRefusesWhatVTKsReaderMishandled)
{
  const std::string vertices = floats({ 0, 0, 0, 10, 0, 0, 0, 10, 0 });
  // Whole files read, in both encodings.
  EXPECT_EQ(toTriangleMesh(readPolyData(writePly("one-triangle.ply", "binary_little_endian",
                             vertices + face(3, { 0, 1, 2 }))))
              .numberOfFaces(),
    1);
  EXPECT_EQ(toTriangleMesh(readPolyData(writePly("one-triangle-ascii.ply", "ascii",
                             "0 0 0\n10 0 0\n0 10 0\n3 0 1 2\n")))
              .numberOfFaces(),
    1);

  // Cut short: VTK's reader read past its buffers (and freed one twice).
  const std::string cut =
    writePly("cut.ply", "binary_little_endian", vertices + face(3, { 0, 1, 2 }).substr(0, 7));
  EXPECT_EQ(
    readError(cut), "'" + cut + "': the file ends inside element 'face' 0 of 1 (truncated)");
  const std::string cutVertices =
    writePly("cut-vertices.ply", "binary_little_endian", vertices.substr(0, 30));
  EXPECT_EQ(readError(cutVertices),
    "'" + cutVertices + "': the file ends inside element 'vertex' 2 of 3 (truncated)");
  const std::string cutAscii = writePly("cut-ascii.ply", "ascii", "0 0 0\n10 0 0\n");
  EXPECT_EQ(readError(cutAscii),
    "'" + cutAscii + "': the file ends before element 'vertex' 2 of 3 (truncated)");

  // A face naming a vertex the file lacks: VTK looked it up out of bounds.
  const std::string far =
    writePly("far-index.ply", "binary_little_endian", vertices + face(3, { 0, 1, 1 << 28 }));
  EXPECT_EQ(
    readError(far), "'" + far + "': element 'face' 0 of 1 names vertex 268435456; the file has 3");
  const std::string negative =
    writePly("negative-index.ply", "ascii", "0 0 0\n10 0 0\n0 10 0\n3 0 -268435456 2\n");
  EXPECT_EQ(readError(negative),
    "'" + negative + "': element 'face' 0 of 1 names vertex -268435456; the file has 3");

  // An unknown type; a list too long for the file.
  const std::string type = writePly("bad-type.ply", "ascii", "", "uchar quad");
  EXPECT_EQ(readError(type), "'" + type + "': unknown PLY property type 'quad'");
  const std::string longList = writePly("long-list.ply", "binary_little_endian",
    vertices + std::string("\xff\xff\xff\x7f", 4), "int int");
  EXPECT_EQ(readError(longList),
    "'" + longList + "': element 'face' 0 of 1 has a list of 2147483647 items");
}

TEST(MeshIO, APlyHeaderNeedsVerticesWithCoordinatesAndFacesWithIndices)
{
  // A mangled property line: VTK skipped it and freed a pointer it never set.
  const std::string path = out + "/mangled.ply";
  std::ofstream(path, std::ios::binary)
    << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    << "property float z\nelement face 1\nobj_infoproperty list uchar int vertex_indices\n"
    << "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(readError(path),
    "'" + path + "': a PLY header line starts with 'obj_infoproperty', no PLY keyword");
  const std::string noIndices =
    writePly("no-indices.ply", "ascii", "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "uchar int");
  std::string text;
  {
    std::ifstream in(noIndices);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  text.replace(text.find("vertex_indices"), 14, "corner_ids");
  std::ofstream(noIndices, std::ios::binary) << text;
  EXPECT_EQ(readError(noIndices),
    "'" + noIndices + "': the PLY face element has no integer list 'vertex_indices'");
  const std::string noZ = out + "/no-z.ply";
  std::ofstream(noZ, std::ios::binary)
    << "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
    << "end_header\n0 0\n";
  EXPECT_EQ(
    readError(noZ), "'" + noZ + "': the PLY vertex element lacks one of the properties x, y and z");
  const std::string noVertices = out + "/no-vertices.ply";
  std::ofstream(noVertices, std::ios::binary)
    << "ply\nformat ascii 1.0\nelement Yertex 1\nproperty float x\nend_header\n0\n";
  EXPECT_EQ(readError(noVertices), "'" + noVertices + "': the PLY file has no vertex element");
  // A header that ends the file, without a newline: nothing is read past the end.
  const std::string bare = out + "/bare-header.ply";
  std::ofstream(bare, std::ios::binary)
    << "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
    << "property float y\nproperty float z\nend_header";
  EXPECT_EQ(
    readError(bare), "'" + bare + "': the file ends inside element 'vertex' 0 of 1 (truncated)");
}

TEST(MeshIO, LegacyVtkCellListsAreWalkedBeforeVTKReadsThem)
{
  const auto write =
    [](const std::string& name, const std::string& version, const std::string& cells)
  {
    const std::string path = out + "/" + name;
    std::ofstream(path, std::ios::binary)
      << "# vtk DataFile Version " << version << "\ntest\nASCII\nDATASET POLYDATA\n"
      << "POINTS 3 float\n0 0 0 10 0 0 0 10 0\n"
      << cells;
    return path;
  };
  EXPECT_EQ(toTriangleMesh(readPolyData(write("old-cells.vtk", "2.0", "POLYGONS 1 4\n3 0 1 2\n")))
              .numberOfFaces(),
    1);
  EXPECT_EQ(toTriangleMesh(readPolyData(write("new-cells.vtk", "5.1",
                             "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 3\n"
                             "CONNECTIVITY vtktypeint64\n0 1 2\n")))
              .numberOfFaces(),
    1);
  // A cell longer than its list: VTK walked the counts past its buffer.
  const std::string longCell = write("long-cell.vtk", "2.0", "POLYGONS 1 4\n5 0 1 2 0\n");
  EXPECT_EQ(readError(longCell),
    "'" + longCell + "': cell 0 of the POLYGONS does not fit in the list's 4 numbers");
  // VTK's reader matches keywords by their start, in any case.
  const std::string shouted = write("shouted.vtk", "x.51", "polygons! 1 4\n5 0 1 2 0\n");
  EXPECT_EQ(readError(shouted),
    "'" + shouted + "': cell 0 of the POLYGONS does not fit in the list's 4 numbers");
  const std::string farId = write("far-id.vtk", "2.0", "POLYGONS 1 4\n3 0 1 7\n");
  EXPECT_EQ(
    readError(farId), "'" + farId + "': cell 0 of the POLYGONS names point 7; the file has 3");
  const std::string offsets = write("bad-offsets.vtk", "5.1",
    "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 5\nCONNECTIVITY vtktypeint64\n0 1 2\n");
  EXPECT_EQ(readError(offsets),
    "'" + offsets + "': the POLYGONS OFFSETS do not rise from 0 to the 3 ids of the CONNECTIVITY");
  // Too few coordinates: the next keyword is no coordinate.
  const std::string few = out + "/few-points.vtk";
  std::ofstream(few, std::ios::binary) << "# vtk DataFile Version 3.0\nfew\nASCII\n"
                                       << "DATASET POLYDATA\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0\n"
                                       << "POLYGONS 1 4\n3 0 1 2\n";
  EXPECT_EQ(readError(few), "'" + few + "': the POINTS hold 'POLYGONS', which is no number");
  const std::string stray = write("stray-word.vtk", "2.0", "POLYGONS 1 4\n3 0 1 2\nv 1 2 3\n");
  EXPECT_EQ(
    readError(stray), "'" + stray + "': the file holds 'v' where a legacy VTK keyword should be");
  const std::string cut = write("cut-points.vtk", "5.1", "");
  std::filesystem::resize_file(cut, std::filesystem::file_size(cut) - 6);
  EXPECT_EQ(readError(cut), "'" + cut + "': the file ends inside the POINTS (truncated)");
}

TEST(MeshIO, LegacyVtkFieldDataIsWalkedBeforeVTKReadsIt)
{
  // VTK's reader dereferenced the null it got from field data it could not read.
  const auto write = [](const std::string& name, const std::string& field)
  {
    const std::string path = out + "/" + name;
    std::ofstream(path, std::ios::binary)
      << "# vtk DataFile Version 4.2\ntest\nASCII\nDATASET POLYDATA\n"
      << "POINTS 3 float\n0 0 0 10 0 0 0 10 0\n"
      << field << "POLYGONS 1 4\n3 0 1 2\n";
    return path;
  };
  EXPECT_EQ(toTriangleMesh(readPolyData(write(
                             "field.vtk", "FIELD FieldData 2\nlabel 1 2 int\n4 5\nNULL_ARRAY\n")))
              .numberOfFaces(),
    1);
  const std::string noCount = write("field-no-count.vtk", "field\xc0\xd8 \xe1\xc0z\n");
  EXPECT_EQ(readError(noCount), "'" + noCount + "': the FIELD line has no count");
  const std::string text = write("field-text.vtk", "FIELD FieldData 1\nnames 1 1 string\nnose\n");
  EXPECT_EQ(readError(text),
    "'" + text +
      "': the FIELD array 'names' has the type 'string'; VIMLOP reads numeric field data only");
  const std::string few = write("field-few.vtk", "FIELD FieldData 1\nlabel 1 3 int\n4 5\n");
  EXPECT_EQ(
    readError(few), "'" + few + "': the FIELD array 'label' hold 'POLYGONS', which is no number");
  const std::string huge =
    write("field-huge.vtk", "FIELD FieldData 1\nlabel 100000 100000 int\n4 5\n");
  EXPECT_EQ(readError(huge),
    "'" + huge +
      "': the FIELD array 'label' promises 100000 components of 100000 tuples; at most 20000000 "
      "values are read");
}

TEST(MeshIO, ABinaryStlWhoseHeaderSaysSolidIsJudgedByItsSize)
{
  // VTK's own binary files start "solid" too; the count said 150 million triangles.
  std::string bytes = "solid VTK generated SLA file";
  bytes.resize(80, '\0');
  const std::uint32_t count = 150000000;
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  bytes.append(100, '\x7f');
  const std::string path = out + "/solid-binary.stl";
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_EQ(readError(path),
    "'" + path +
      "': truncated or corrupt binary STL (150000000 triangles need 7500000084 bytes, the file has "
      "184)");
}

TEST(MeshIO, AnObjFaceNamesOnlyWhatIsDefinedBeforeIt)
{
  const auto write = [](const std::string& name, const std::string& faces)
  {
    const std::string path = out + "/" + name;
    std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n" << faces;
    return path;
  };
  EXPECT_EQ(toTriangleMesh(readPolyData(write("fine.obj", "f 1/1 2/1 -1/1\n"))).numberOfFaces(), 1);
  // Texture index 0 became -1 inside VTK's reader, read out of bounds.
  const std::string zero = write("zero-texture.obj", "f 1/1 2/1 3/0\n");
  EXPECT_EQ(readError(zero),
    "'" + zero + "': line 5 names texture coordinate '0'; 1 are defined before it");
  const std::string far = write("far-vertex.obj", "f 1/1 2/1 4/1\n");
  EXPECT_EQ(readError(far), "'" + far + "': line 5 names vertex '4'; 3 are defined before it");
  const std::string normal = write("no-normal.obj", "f 1/1/1 2/1/1 3/1/1\n");
  EXPECT_EQ(
    readError(normal), "'" + normal + "': line 5 names normal '1'; 0 are defined before it");
  // Normals in the file but not at a corner: VTK looked one up out of bounds.
  const std::string missing = write("corner-without-normal.obj", "vn 0 0 1\nf 1/1/1 2/1/1 3/1\n");
  EXPECT_EQ(readError(missing),
    "'" + missing +
      "': line 6 has a corner '3/1' without the texture coordinate or normal the file defines "
      "for every corner");
  const std::string words = write("vertex-words.obj", "v 0 zero 0\nf 1/1 2/1 3/1\n");
  EXPECT_EQ(readError(words), "'" + words + "': line 5 is a 'v' line without its numbers");
  // "1/" is no corner: VTK's reader took it for one with a texture
  // coordinate and read a null array.
  const std::string slash = out + "/trailing-slash.obj";
  std::ofstream(slash) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2/ 3/\n";
  EXPECT_EQ(readError(slash), "'" + slash + "': line 4 has a corner '1/' that ends with '/'");
  const std::string twoSlashes = out + "/normal-slash.obj";
  std::ofstream(twoSlashes) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/\n";
  EXPECT_EQ(
    readError(twoSlashes), "'" + twoSlashes + "': line 6 has a corner '3/1/' that ends with '/'");
}

namespace
{

/// A triangle as VTK XML polydata whose points array has the `header` (and
/// `data`) given: appended raw, or inline base64 (`base64Points`).
std::string xmlTriangle(const std::string& name, const std::string& compressor,
  const std::string& header, const std::string& base64Points = std::string())
{
  const std::string path = out + "/" + name + ".vtp";
  std::ofstream file(path, std::ios::binary);
  file << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
          "byte_order=\"LittleEndian\" header_type=\"UInt32\""
       << (compressor.empty() ? "" : " compressor=\"" + compressor + "\"")
       << ">\n<PolyData><Piece NumberOfPoints=\"3\" NumberOfPolys=\"1\">\n<Points>"
       << (base64Points.empty()
              ? "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"appended\" "
                "offset=\"0\"/>"
              : "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">" +
                base64Points + "</DataArray>")
       << "</Points>\n<Polys><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 "
          "2</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">3</DataArray>"
          "</Polys>\n</Piece></PolyData>\n<AppendedData encoding=\"raw\">\n_"
       << header << "\n</AppendedData>\n</VTKFile>\n";
  return path;
}

std::string uint32s(std::initializer_list<std::uint32_t> values)
{
  std::string bytes;
  for (std::uint32_t v : values)
  {
    for (int i = 0; i < 4; ++i)
    {
      bytes.push_back(static_cast<char>(v >> (8 * i) & 0xff));
    }
  }
  return bytes;
}

} // namespace

TEST(MeshFiles, AVtkXmlArrayHeaderIsJudgedBeforeVTKAllocatesWhatItClaims)
{
  // VTK would allocate 2^30 block sizes (8 GB) for this 12-byte header.
  const std::string blocks =
    xmlTriangle("xml-blocks", "vtkZLibDataCompressor", uint32s({ 1u << 30, 32768, 0 }));
  EXPECT_EQ(readError(blocks),
    "'" + blocks +
      "': the VTK XML array 0 declares 1073741824 compressed blocks, more than its 28 bytes can "
      "list");
  const std::string blockSize =
    xmlTriangle("xml-block-size", "vtkZLibDataCompressor", uint32s({ 1, 4000000000u, 36, 20 }));
  EXPECT_EQ(readError(blockSize),
    "'" + blockSize +
      "': the VTK XML array 0 declares blocks of 4000000000 bytes (the last of 36); blocks of at "
      "most 67108864 bytes are read");
  const std::string compressedSize =
    xmlTriangle("xml-compressed", "vtkZLibDataCompressor", uint32s({ 1, 36, 36, 900 }));
  EXPECT_EQ(readError(compressedSize),
    "'" + compressedSize +
      "': the VTK XML array 0 declares 900 compressed bytes or more and 28 are left");
  // Inline base64, not compressed: "AAAAQA==" is 2^30 bytes announced.
  const std::string inline64 = xmlTriangle("xml-inline", "", "", "AAAAQA==");
  EXPECT_EQ(readError(inline64),
    "'" + inline64 + "': the VTK XML array 0 declares 1073741824 bytes and 3 are left");
  const std::string cut = xmlTriangle("xml-cut", "vtkZLibDataCompressor", "", "AAAA");
  EXPECT_EQ(readError(cut), "'" + cut + "': the VTK XML array 0 is cut off in its header");
}
