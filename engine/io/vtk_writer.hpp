// Writes a frame as a VTK XML unstructured grid (.vtu, binary, zlib-compressed) through VTK's writer.
// The only file of the engine that includes VTK headers is vtk_writer.cpp (build speed).
#pragma once

#include <string>

#include "engine/io/frame.hpp"

namespace loom {

// Writes to a temporary name and renames; throws RunError on failure.
void write_vtu(const std::string& path, const Frame& frame);

}  // namespace loom
