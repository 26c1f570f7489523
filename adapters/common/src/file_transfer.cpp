#include "cosim/link/file_transfer.h"

#include <cerrno>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "cosim/link/errors.h"
#include "cosim/util/errors.h"

namespace cosim::link {

namespace fs = std::filesystem;

void packFolder(const fs::path& root, FileList& out) {
  std::size_t total = 0;
  if (!fs::is_directory(root)) return;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator();
       ++it) {
    if (!it->is_regular_file() || it->is_symlink()) continue;
    std::ifstream in(it->path(), std::ios::binary);
    if (!in) {
      const int err = errno;
      throw Error(kindOfErrno(err), "cannot read " + it->path().string() + " to send it");
    }
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    total += bytes.size();
    if (total > kMaxTransferBytes) {
      throw InputError("the files of " + root.string() + " are more than " +
                       std::to_string(kMaxTransferBytes >> 20) +
                       " MiB, too much to send over the link; give the participant the "
                       "run folder on a shared filesystem instead (no --workdir)");
    }
    auto* f = out.Add();
    f->set_path(fs::relative(it->path(), root).generic_string());
    f->set_content(std::move(bytes));
    f->set_mode(static_cast<unsigned>(it->status().permissions() & fs::perms::mask));
  }
}

void unpackFiles(const FileList& files, const fs::path& root) {
  for (const auto& f : files) {
    const fs::path rel(f.path());
    bool safe = !f.path().empty() && rel.is_relative() && !rel.has_root_name();
    for (const auto& part : rel) safe = safe && part != ".." && part != "." && !part.empty();
    if (!safe) {
      throw ProtocolError("refusing a file sent as '" + f.path() +
                          "': only paths inside the participant's folder are accepted");
    }
    const fs::path target = root / rel;
    fs::create_directories(target.parent_path());
    {
      std::ofstream out(target, std::ios::binary | std::ios::trunc);
      out.write(f.content().data(), static_cast<std::streamsize>(f.content().size()));
      if (!out) {
        const int err = errno;
        throw Error(kindOfErrno(err), "cannot write " + target.string() + " (disk full?)");
      }
    }
    if (f.mode() != 0) fs::permissions(target, static_cast<fs::perms>(f.mode()) & fs::perms::mask);
  }
}

}  // namespace cosim::link
