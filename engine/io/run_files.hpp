// The files a run keeps in its output directory besides its frames' content: which frames and checkpoints
// belong to the run, where checkpoints go, and which one a restart takes.
//   <stem>_NNNNNN.vtu, <stem>_NNNNNN_particles.vtp, <stem>_NNNNNN_grid.vtu   frames of step NNNNNN
//   checkpoint_NNNNNN.loom                                                   the checkpoint of step NNNNNN
#pragma once

#include <string>
#include <vector>

namespace loom {

// Creates the output directory and checks that files can be written in it. Throws InputError (bad
// input, exit 2) naming `origin` (the --out option or the scene's output.directory key) if not.
void prepare_output_directory(const std::string& directory, const std::string& origin);

// Removes the frames of the scene stem whose step is after `after_step` (all of them for -1): those of an
// earlier run, which would otherwise sit beside the new ones, or those written after a checkpoint. Frames of
// step `after_step` itself go too unless `kept` names them: the last state a stopped run wrote after its
// checkpoint, which the continued run writes again if it is one of its frames.
void remove_frames(const std::string& directory, const std::string& stem, int after_step, const std::vector<std::string>& kept = {});

std::string checkpoint_path(const std::string& directory, int step);
// Removes every checkpoint of the directory but the one of step `keep` (-1: all).
void remove_checkpoints(const std::string& directory, int keep);
// The checkpoint a restart continues from: `path` itself if it is a file, else the newest checkpoint in
// the directory. Throws InputError if there is none.
std::string find_checkpoint(const std::string& path);

}  // namespace loom
