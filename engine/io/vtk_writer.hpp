// Writes a frame as a VTK XML unstructured grid (.vtu) or poly data (.vtp), binary, zlib-compressed, through VTK's writers.
// The only file of the engine that includes VTK headers is vtk_writer.cpp (build speed).
#pragma once

#include <string>

#include "engine/io/frame.hpp"

namespace loom {

// Writes to a temporary name and renames; throws RunError on failure.
void write_vtu(const std::string& path, const Frame& frame);
// A point cloud (MPM particles) as VTK XML poly data (.vtp): the frame's points, one vertex each, and its
// point arrays (cells and cell arrays are ignored).
void write_vtp(const std::string& path, const Frame& frame);

}  // namespace loom
