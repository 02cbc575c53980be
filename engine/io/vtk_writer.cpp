#include "engine/io/vtk_writer.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <filesystem>

#include "engine/core/errors.hpp"
#include "engine/io/files.hpp"

namespace loom {
namespace {

vtkNew<vtkDoubleArray> to_vtk(const FrameArray& a) {
  vtkNew<vtkDoubleArray> v;
  v->SetName(a.name.c_str());
  v->SetNumberOfComponents(a.components);
  v->SetNumberOfTuples(vtkIdType(a.values.size() / std::size_t(a.components)));
  std::copy(a.values.begin(), a.values.end(), v->GetPointer(0));
  return v;
}

}  // namespace

void write_vtu(const std::string& path, const Frame& frame) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(frame.n_points());
  for (Index i = 0; i < frame.n_points(); ++i)
    points->SetPoint(i, frame.points[3 * std::size_t(i)], frame.points[3 * std::size_t(i) + 1], frame.points[3 * std::size_t(i) + 2]);

  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(frame.n_cells() + 1);
  offsets->SetValue(0, 0);
  for (Index c = 0; c < frame.n_cells(); ++c) offsets->SetValue(c + 1, frame.offsets[std::size_t(c)]);
  connectivity->SetNumberOfValues(vtkIdType(frame.connectivity.size()));
  for (std::size_t k = 0; k < frame.connectivity.size(); ++k) connectivity->SetValue(vtkIdType(k), frame.connectivity[k]);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  vtkNew<vtkUnsignedCharArray> types;
  types->SetNumberOfValues(frame.n_cells());
  for (Index c = 0; c < frame.n_cells(); ++c) types->SetValue(c, frame.cell_types[std::size_t(c)]);

  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->SetCells(types, cells);
  for (const auto& a : frame.point_arrays) grid->GetPointData()->AddArray(to_vtk(a));
  for (const auto& a : frame.cell_arrays) grid->GetCellData()->AddArray(to_vtk(a));

  const std::string tmp = temporary_name(path);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(tmp.c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToZLib();
  writer->EncodeAppendedDataOff();
  LOOM_CHECK(writer->Write() == 1, RunError, "VTK could not write " << tmp);
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  LOOM_CHECK(!ec, RunError, "cannot rename " << tmp << " to " << path << ": " << ec.message());
}

}  // namespace loom
