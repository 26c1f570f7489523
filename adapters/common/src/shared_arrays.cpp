#include "cosim/link/shared_arrays.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "cosim.pb.h"
#include "cosim/link/errors.h"

namespace cosim::link {

namespace {

constexpr std::size_t kAlign = 64;           // each array on its own cache lines
constexpr std::size_t kSmallest = 1U << 20;  // bytes of the first object
constexpr std::size_t kPage = 4096;

std::size_t aligned(std::size_t bytes) { return (bytes + kAlign - 1) / kAlign * kAlign; }

}  // namespace

// ---- the sender -----------------------------------------------------------------------------

SharedArrayWriter::SharedArrayWriter(std::string prefix, std::string side)
    : prefix_(std::move(prefix)), side_(std::move(side)) {}

SharedArrayWriter::~SharedArrayWriter() {
  for (auto& r : regions_) release(r);
}

void SharedArrayWriter::release(Region& r) {
  if (r.linked) shm_unlink(r.name.c_str());
  r.linked = false;
  if (r.base != nullptr) munmap(r.base, r.capacity);
  r.base = nullptr;
}

void SharedArrayWriter::startOver() {
  // The peer has answered the message that named these objects: it has them open
  for (auto& r : regions_) {
    if (r.linked) shm_unlink(r.name.c_str());
    r.linked = false;
  }
  // Only the last object is written again; the peer is done with the earlier ones
  while (regions_.size() > 1) {
    release(regions_.front());
    regions_.erase(regions_.begin());
  }
  used_ = 0;
}

bool SharedArrayWriter::grow(std::size_t at_least) {
  const std::size_t last = regions_.empty() ? 0 : regions_.back().capacity;
  const std::size_t capacity =
      (std::max({at_least, 2 * last, kSmallest}) + kPage - 1) / kPage * kPage;
  Region r;
  r.name = prefix_ + "-" + side_ + "-" + std::to_string(next_++);
  const int fd = shm_open(r.name.c_str(), O_RDWR | O_CREAT | O_EXCL, S_IRUSR | S_IWUSR);
  if (fd < 0) {
    failure_ = "cannot create the shared memory object " + r.name + ": " + std::strerror(errno);
    return false;
  }
  r.linked = true;
  // The pages are reserved now: a full /dev/shm is an error here, not a SIGBUS while writing
  const int reserved = posix_fallocate(fd, 0, static_cast<off_t>(capacity));
  if (reserved != 0) {
    failure_ = "cannot reserve " + std::to_string(capacity >> 20) + " MiB of shared memory for " +
               r.name + " (/dev/shm full?): " + std::strerror(reserved);
    close(fd);
    shm_unlink(r.name.c_str());
    return false;
  }
  void* base = mmap(nullptr, capacity, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  close(fd);
  if (base == MAP_FAILED) {
    failure_ = "cannot map the shared memory object " + r.name + ": " + std::strerror(errno);
    shm_unlink(r.name.c_str());
    return false;
  }
  r.base = static_cast<char*>(base);
  r.capacity = capacity;
  regions_.push_back(std::move(r));
  used_ = 0;
  return true;
}

bool SharedArrayWriter::put(const double* values, std::size_t n, wire::SharedExtent& where) {
  if (!failure_.empty()) return false;
  if (answered_) {
    startOver();
    answered_ = false;
  }
  const std::size_t bytes = n * sizeof(double);
  if (regions_.empty() || used_ + bytes > regions_.back().capacity) {
    if (!grow(bytes)) {  // said once, in the participant's log; the run goes on without it
      std::cerr << "[" << side_ << "] " << failure_
                << "; the per-parcel values go in the peer messages instead" << std::endl;
      return false;
    }
  }
  Region& r = regions_.back();
  if (bytes > 0) std::memcpy(r.base + used_, values, bytes);
  where.set_region(r.name);
  where.set_offset(used_);
  used_ = aligned(used_ + bytes);
  return true;
}

const double* SharedArrayWriter::at(const wire::SharedExtent& where, std::size_t n) const {
  for (const auto& r : regions_) {
    if (r.name == where.region() && where.offset() + n * sizeof(double) <= r.capacity)
      return reinterpret_cast<const double*>(r.base + where.offset());
  }
  return nullptr;
}

// ---- the receiver ---------------------------------------------------------------------------

SharedArrayReader::SharedArrayReader(std::string prefix) : prefix_(std::move(prefix)) {}

SharedArrayReader::~SharedArrayReader() {
  for (auto& [name, m] : mapped_) munmap(const_cast<char*>(m.base), m.size);
}

void SharedArrayReader::newMessage() {
  // The peer writes only its newest object once it has had an answer: the older ones go
  for (auto it = mapped_.begin(); it != mapped_.end();) {
    if (it->second.number < newest_) {
      munmap(const_cast<char*>(it->second.base), it->second.size);
      it = mapped_.erase(it);
    } else {
      ++it;
    }
  }
}

const double* SharedArrayReader::at(const wire::SharedExtent& where, std::size_t n) {
  const std::string& name = where.region();
  if (name.rfind(prefix_ + "-", 0) != 0 || name.find('/', 1) != std::string::npos)
    throw ProtocolError("the peer named shared memory '" + name + "', which is not this run's (" +
                        prefix_ + "-...)");
  auto it = mapped_.find(name);
  if (it == mapped_.end()) {
    const int fd = shm_open(name.c_str(), O_RDONLY, 0);
    if (fd < 0)
      throw ProtocolError("cannot open the peer's shared memory " + name + ": " +
                          std::strerror(errno));
    struct stat st {};
    if (fstat(fd, &st) != 0 || st.st_size <= 0) {
      close(fd);
      throw ProtocolError("the peer's shared memory " + name + " is empty");
    }
    const auto size = static_cast<std::size_t>(st.st_size);
    void* base = mmap(nullptr, size, PROT_READ, MAP_SHARED, fd, 0);
    close(fd);
    if (base == MAP_FAILED)
      throw ProtocolError("cannot map the peer's shared memory " + name + ": " +
                          std::strerror(errno));
    const auto dash = name.rfind('-');
    const unsigned long number = std::strtoul(name.c_str() + dash + 1, nullptr, 10);
    newest_ = std::max(newest_, number);
    it = mapped_.emplace(name, Mapping{static_cast<const char*>(base), size, number}).first;
  }
  const Mapping& m = it->second;
  if (where.offset() % sizeof(double) != 0 || where.offset() > m.size ||
      n > (m.size - where.offset()) / sizeof(double))
    throw ProtocolError("the peer's shared memory " + name + " holds " + std::to_string(m.size) +
                        " bytes, too few for " + std::to_string(n) + " values at byte " +
                        std::to_string(where.offset()));
  return reinterpret_cast<const double*>(m.base + where.offset());
}

// ---- a run's objects ------------------------------------------------------------------------

std::string sharedArraysPrefix(const std::string& run_id) {
  return "/cosim-" + std::to_string(getuid()) + "-" + run_id;
}

void removeSharedArrays(const std::string& prefix) {
  // Linux lists a POSIX shared memory object as /dev/shm/<name>
  DIR* dir = opendir("/dev/shm");
  if (dir == nullptr) return;
  const std::string mine = prefix.substr(1) + "-";
  std::vector<std::string> found;
  while (const dirent* e = readdir(dir)) {
    const std::string name = e->d_name;
    if (name.rfind(mine, 0) == 0) found.push_back("/" + name);
  }
  closedir(dir);
  for (const auto& name : found) shm_unlink(name.c_str());
}

}  // namespace cosim::link
