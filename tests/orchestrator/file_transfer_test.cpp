// Files sent over the link to and from a participant with a folder of its own
// (cosim/link/file_transfer.h): a folder arrives as it was, with its modes, and nothing a peer
// sends is written outside the folder it belongs to.
#include "cosim/link/file_transfer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace cosim::link;

namespace {

fs::path fresh(const std::string& name) {
  const fs::path p =
      fs::temp_directory_path() / ("cosim-transfer-" + name + "-" + std::to_string(getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string text(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(FileTransfer, AFolderArrivesAsItWasWithItsModes) {
  const fs::path from = fresh("from"), to = fresh("to");
  fs::create_directories(from / "system");
  std::ofstream(from / "system/controlDict") << "application cosimFoam;\n";
  const std::string binary("\0\1\2\xff restart", 12);
  std::ofstream(from / "restart.bin", std::ios::binary) << binary;
  std::ofstream(from / "run.sh") << "#!/bin/sh\n";
  fs::permissions(from / "run.sh", fs::perms::owner_all | fs::perms::group_read);
  fs::create_symlink(from / "restart.bin", from / "link");  // not followed, not sent

  FileList files;
  packFolder(from, files);
  EXPECT_EQ(files.size(), 3);
  unpackFiles(files, to);
  EXPECT_EQ(text(to / "system/controlDict"), "application cosimFoam;\n");
  EXPECT_EQ(text(to / "restart.bin"), binary);
  EXPECT_EQ(fs::status(to / "run.sh").permissions() & fs::perms::mask,
            fs::perms::owner_all | fs::perms::group_read);
  EXPECT_FALSE(fs::exists(to / "link"));
  fs::remove_all(from);
  fs::remove_all(to);
}

TEST(FileTransfer, NothingIsWrittenOutsideTheFolder) {
  const fs::path root = fresh("root");
  for (const std::string bad : {"../escape", "/tmp/abs", "a/../../b", "", "./a"}) {
    SCOPED_TRACE(bad);
    FileList files;
    auto* f = files.Add();
    f->set_path(bad);
    f->set_content("x");
    try {
      unpackFiles(files, root / "in");
      ADD_FAILURE() << "accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("only paths inside"), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(fs::exists(root / "escape"));
  EXPECT_FALSE(fs::exists(root / "b"));
  fs::remove_all(root);
}
