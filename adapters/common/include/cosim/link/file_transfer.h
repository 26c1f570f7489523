// Files sent over the link to and from a participant that has a folder of its own on its node
// and does not see the run folder (no shared filesystem; docs/cluster.md): the case files and
// restart in the Welcome, checkpoints in CheckpointWritten.
#pragma once

#include <cstddef>
#include <filesystem>

#include "cosim.pb.h"

namespace cosim::link {

using FileList = google::protobuf::RepeatedPtrField<wire::FileData>;

// At most this many bytes in one message's files (protobuf's own bound is 2 GiB).
inline constexpr std::size_t kMaxTransferBytes = std::size_t{1} << 30;

// Every regular file under `root` (recursively, symlinks not followed), paths relative to it.
// Throws std::runtime_error naming the folder when it holds more than kMaxTransferBytes.
void packFolder(const std::filesystem::path& root, FileList& out);

// Writes the files under `root` (created if needed), each with its mode. Refuses (throws
// std::runtime_error naming the path) an absolute path, a '..' or an empty component: nothing
// a peer sends reaches a file outside `root`.
void unpackFiles(const FileList& files, const std::filesystem::path& root);

}  // namespace cosim::link
