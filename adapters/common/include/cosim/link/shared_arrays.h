// Per-parcel arrays through shared memory between the two peers of one machine
// (coupling.data_path: peer over ipc://; docs/design.md section 5). A Field's values then stay
// out of the protobuf message: the sender writes them once into a POSIX shared memory object
// of its own and the message carries where (wire::SharedExtent); the receiver copies them once
// out of it. The message, the ids, the checks and the order of the exchange are the wire's.
//
// The exchange is request and reply, so a sender reuses its object only after the peer has
// answered the message that used it: a peer calls answered() when a message of the other comes,
// and the next put() starts over. Objects are named `<prefix>-<side>-<n>` (prefix from
// Welcome.peer.shared_memory, the run's own: /cosim-UID-RUN); a name is unlinked as soon as the
// peer has had it, and the orchestrator removes what a killed peer left (removeSharedArrays).
// Where shared memory cannot be had (no /dev/shm, or full), put() says so and the values travel
// in the message, as across nodes.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace cosim::wire {
class SharedExtent;
}

namespace cosim::link {

class SharedArrayWriter {
 public:
  SharedArrayWriter(std::string prefix, std::string side);
  ~SharedArrayWriter();
  SharedArrayWriter(const SharedArrayWriter&) = delete;
  SharedArrayWriter& operator=(const SharedArrayWriter&) = delete;

  // The peer answered: it has read what this writer put, which the next put() may overwrite.
  void answered() { answered_ = true; }
  // Writes n values and says where; false (nothing written) when no shared memory can be had.
  bool put(const double* values, std::size_t n, wire::SharedExtent& where);
  // The values this writer put at `where`, until the next put() after an answer (nullptr if
  // they are not this writer's).
  const double* at(const wire::SharedExtent& where, std::size_t n) const;
  // Why shared memory could not be had (empty while it could).
  const std::string& failure() const { return failure_; }

 private:
  struct Region {
    std::string name;
    char* base = nullptr;
    std::size_t capacity = 0;
    bool linked = false;
  };
  void startOver();  // a new message after an answer: names unlinked, older objects gone
  bool grow(std::size_t at_least);
  static void release(Region& r);
  std::string prefix_;
  std::string side_;
  std::vector<Region> regions_;  // the last is written; earlier ones are read by the peer
  std::size_t used_ = 0;         // bytes of the last region in this message
  unsigned next_ = 0;            // the next object's number
  bool answered_ = false;        // since the last put()
  std::string failure_;
};

class SharedArrayReader {
 public:
  explicit SharedArrayReader(std::string prefix);
  ~SharedArrayReader();
  SharedArrayReader(const SharedArrayReader&) = delete;
  SharedArrayReader& operator=(const SharedArrayReader&) = delete;

  // A message of the peer came: the objects older than the newest one seen are unmapped (the
  // peer moved to a bigger one and no longer writes them).
  void newMessage();
  // The n values at `where`; ProtocolError naming the object when it is not the run's, cannot
  // be opened or is too short.
  const double* at(const wire::SharedExtent& where, std::size_t n);

 private:
  struct Mapping {
    const char* base = nullptr;
    std::size_t size = 0;
    unsigned long number = 0;  // the n of its name
  };
  std::string prefix_;
  std::map<std::string, Mapping> mapped_;
  unsigned long newest_ = 0;  // the highest n seen
};

// What one peer holds: its own objects to write and the other's to read. received() when a
// message of the other peer comes.
struct SharedArrays {
  SharedArrays(const std::string& prefix, const std::string& side)
      : out(prefix, side), in(prefix) {}
  void received() {
    in.newMessage();
    out.answered();
  }
  SharedArrayWriter out;
  SharedArrayReader in;
};

// The shared memory objects of a run (prefix /cosim-UID-RUN): the names to give the peers and
// the removal of whatever a peer that was killed left behind.
std::string sharedArraysPrefix(const std::string& run_id);
void removeSharedArrays(const std::string& prefix);

}  // namespace cosim::link
