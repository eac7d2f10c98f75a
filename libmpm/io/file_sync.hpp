// Durable replacement of a file by its temporary (NAME.tmp, then rename): the temporary's data are
// forced to the disk (fsync) before the rename, so that a power cut leaves the old file or the new
// one, never the new name on blocks that were not written. Used by every atomic write of a run's
// outputs: frames, .pvd indexes, CSV truncation, run.json and the checkpoint, whose directory is
// synced after the rename too (the new name itself survives a power cut).
#pragma once
#include <filesystem>

namespace cleave::io {

// fsync(2) of an open descriptor, retried when a signal interrupts it. Returns 0 or the errno; a
// file system that cannot sync (EINVAL, ENOTSUP: some special ones) counts as synced.
int sync_descriptor(int fd);

// fsync(2) of `file`'s data, opened read-only (Linux flushes a file's data whatever the
// descriptor's access mode). Returns 0, or the errno of open or fsync (as sync_descriptor).
int sync_file(const std::filesystem::path& file);

// fsync(2) of a directory, so that a rename in it survives a power cut. Best effort: some file
// systems refuse to sync a directory, and the rename has happened either way.
void sync_directory(const std::filesystem::path& dir);

}  // namespace cleave::io
