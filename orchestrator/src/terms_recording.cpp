#include "terms_recording.h"

#include <sys/mman.h>

#include <cstdint>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include "cosim.pb.h"
#include "cosim/link/particle_wire.h"

namespace cosim::orchestrator {

namespace {

// A block: three parts (forcing, exchange, zone membership), each its length then its bytes.
constexpr std::size_t kParts = 3;

std::string wireBytes(const link::ParticleData& d) {
  wire::FieldSet set;
  link::toWire(d, set);
  return set.SerializeAsString();
}

link::ParticleData fromBytes(const char* data, std::size_t size) {
  wire::FieldSet set;
  if (!set.ParseFromArray(data, static_cast<int>(size)))
    throw std::logic_error("cosim bench: a recorded interval cannot be read back");
  return link::fromWire(set);
}

}  // namespace

TermsRecording::~TermsRecording() {
  for (const Block& b : blocks_) munmap(b.data, b.bytes);
}

void TermsRecording::push_back(const models::CouplingTerms& terms) {
  const std::string parts[kParts] = {wireBytes(terms.forcing), wireBytes(terms.exchange),
                                     std::string(terms.in_zone.begin(), terms.in_zone.end())};
  std::size_t bytes = 0;
  for (const auto& p : parts) bytes += sizeof(std::uint64_t) + p.size();
  void* data = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (data == MAP_FAILED) throw std::bad_alloc();
  char* at = static_cast<char*>(data);
  for (const auto& p : parts) {
    const std::uint64_t n = p.size();
    std::memcpy(at, &n, sizeof n);
    std::memcpy(at + sizeof n, p.data(), p.size());
    at += sizeof n + p.size();
  }
  blocks_.push_back({data, bytes});
}

models::CouplingTerms TermsRecording::operator[](std::size_t k) const {
  const Block& b = blocks_.at(k);
  const char* at = static_cast<const char*>(b.data);
  auto next = [&at] {
    std::uint64_t n = 0;
    std::memcpy(&n, at, sizeof n);
    const char* part = at + sizeof n;
    at = part + n;
    return std::pair<const char*, std::size_t>{part, static_cast<std::size_t>(n)};
  };
  models::CouplingTerms t;
  const auto [forcing, nf] = next();
  t.forcing = fromBytes(forcing, nf);
  const auto [exchange, ne] = next();
  t.exchange = fromBytes(exchange, ne);
  const auto [zone, nz] = next();
  t.in_zone.assign(zone, zone + nz);
  return t;
}

}  // namespace cosim::orchestrator
