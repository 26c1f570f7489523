// ParticleData: per-particle arrays keyed by particle id, the in-memory twin of wire::FieldSet
// (particle_wire.h converts). Contiguous arrays (x,y,z interleaved for vectors) so models and
// solvers can loop over them. Part of the contract library (cosim_contract): no ZeroMQ, no
// protobuf.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace cosim::link {

class ParticleData {
 public:
  std::vector<std::int64_t> ids;

  std::size_t size() const { return ids.size(); }
  bool has(const std::string& name) const { return fields_.count(name) != 0; }

  // Field storage, created zero-filled with the right length if absent.
  std::vector<double>& field(const std::string& name);
  // Read-only access; throws std::out_of_range naming the field if absent.
  const std::vector<double>& get(const std::string& name) const;
  // Resize every field to the current ids.size().
  void resizeFields();
  void erase(const std::string& name) { fields_.erase(name); }
  // Moves a field out (empty if absent) and removes it, without the copy of get().
  std::vector<double> take(const std::string& name);
  std::vector<std::string> names() const;
  // Every field by name, for a pass over all of them without copying the names.
  const std::map<std::string, std::vector<double>>& fields() const { return fields_; }

  // Keep only the named fields (packets carry what the scene uses, nothing else); from a
  // temporary (std::move(d).select(...)) the fields are moved, not copied.
  ParticleData select(const std::vector<std::string>& names) const&;
  ParticleData select(const std::vector<std::string>& names) &&;

  // Map id -> index (built on demand).
  std::map<std::int64_t, std::size_t> index() const;

  // Sets a field to `values` (moved in, not checked: the caller knows its length).
  void put(const std::string& name, std::vector<double> values) {
    fields_[name] = std::move(values);
  }

 private:
  std::map<std::string, std::vector<double>> fields_;
};

}  // namespace cosim::link
