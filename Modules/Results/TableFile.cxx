#include "TableFile.h"

#include <vimlop/Core/FileError.h>

#include <filesystem>

#include <vtkErrorCode.h>
#include <vtkNew.h>
#include <vtkTable.h>
#include <vtkXMLTableWriter.h>

namespace vimlop::detail
{

void writeTableFile(vtkTable* table, const std::string& path)
{
  // Asked first: VTK would print its own error for a missing folder.
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!folder.empty() && !std::filesystem::is_directory(folder, ec))
  {
    throwFileError(path, "cannot write the table: its folder does not exist");
  }
  vtkNew<vtkXMLTableWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(table);
  writer->SetDataModeToBinary();
  if (writer->Write() != 1 || writer->GetErrorCode() != vtkErrorCode::NoError)
  {
    throwFileError(path, "cannot write the table");
  }
}

} // namespace vimlop::detail
