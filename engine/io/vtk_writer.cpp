#include "engine/io/vtk_writer.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkStringArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
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

void add_notes(vtkDataObject* data, const Frame& frame) {
  for (const auto& [name, text] : frame.notes) {
    vtkNew<vtkStringArray> note;
    note->SetName(name.c_str());
    note->InsertNextValue(text);
    data->GetFieldData()->AddArray(note);
  }
}

vtkNew<vtkPoints> to_vtk_points(const Frame& frame) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(frame.n_points());
  for (Index i = 0; i < frame.n_points(); ++i)
    points->SetPoint(i, frame.points[3 * std::size_t(i)], frame.points[3 * std::size_t(i) + 1], frame.points[3 * std::size_t(i) + 2]);
  return points;
}

// Writes through `writer` to a temporary name, then renames (DESIGN §6).
template <class Writer>
void write_atomically(Writer& writer, const std::string& path) {
  const std::string tmp = temporary_name(path);
  writer->SetFileName(tmp.c_str());
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToZLib();
  writer->EncodeAppendedDataOff();
  LOOM_CHECK(writer->Write() == 1, RunError, "VTK could not write " << tmp);
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  LOOM_CHECK(!ec, RunError, "cannot rename " << tmp << " to " << path << ": " << ec.message());
}

}  // namespace

void write_vtp(const std::string& path, const Frame& frame) {
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(to_vtk_points(frame));
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(frame.n_points() + 1);
  connectivity->SetNumberOfValues(frame.n_points());
  for (Index i = 0; i <= frame.n_points(); ++i) offsets->SetValue(i, i);
  for (Index i = 0; i < frame.n_points(); ++i) connectivity->SetValue(i, i);
  vtkNew<vtkCellArray> verts;
  verts->SetData(offsets, connectivity);
  cloud->SetVerts(verts);
  for (const auto& a : frame.point_arrays) cloud->GetPointData()->AddArray(to_vtk(a));
  add_notes(cloud, frame);
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(cloud);
  write_atomically(writer, path);
}

void write_vtu(const std::string& path, const Frame& frame) {
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
  grid->SetPoints(to_vtk_points(frame));
  grid->SetCells(types, cells);
  for (const auto& a : frame.point_arrays) grid->GetPointData()->AddArray(to_vtk(a));
  for (const auto& a : frame.cell_arrays) grid->GetCellData()->AddArray(to_vtk(a));
  add_notes(grid, frame);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  write_atomically(writer, path);
}

}  // namespace loom
