// A .vtu frame read back through VTK's own reader, as ParaView reads it (the scene tests of the output files).
#pragma once

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <gtest/gtest.h>

#include <string>

namespace loom::testing {

struct VtuFrame {
  vtkSmartPointer<vtkUnstructuredGrid> grid;
  vtkDataArray* point(const char* name) const { return grid->GetPointData()->GetArray(name); }
  vtkDataArray* cell(const char* name) const { return grid->GetCellData()->GetArray(name); }
};

inline VtuFrame read_vtu(const std::string& path) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  EXPECT_TRUE(reader->CanReadFile(path.c_str())) << path;
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetErrorCode(), 0) << path;
  VtuFrame f;
  f.grid = reader->GetOutput();
  return f;
}

}  // namespace loom::testing
