#include "cosim/link/particle_data.h"

#include <algorithm>

#include "cosim/link/fields.h"

namespace cosim::link {

using field::componentsOrOne;

std::vector<double>& ParticleData::field(const std::string& name) {
  auto& v = fields_[name];
  const std::size_t want = ids.size() * componentsOrOne(name);
  if (v.size() != want) v.resize(want, 0.0);
  return v;
}

const std::vector<double>& ParticleData::get(const std::string& name) const {
  auto it = fields_.find(name);
  if (it == fields_.end()) {
    throw std::out_of_range("particle field '" + name + "' is not in this packet");
  }
  return it->second;
}

std::vector<double> ParticleData::take(const std::string& name) {
  auto node = fields_.extract(name);
  return node ? std::move(node.mapped()) : std::vector<double>{};
}

void ParticleData::resizeFields() {
  for (auto& [name, v] : fields_) v.resize(ids.size() * componentsOrOne(name), 0.0);
}

std::vector<std::string> ParticleData::names() const {
  std::vector<std::string> v;
  v.reserve(fields_.size());
  for (const auto& [k, x] : fields_) v.push_back(k);
  return v;
}

ParticleData ParticleData::select(const std::vector<std::string>& wanted) const& {
  ParticleData out;
  out.ids = ids;
  for (const auto& n : wanted) {
    auto it = fields_.find(n);
    if (it != fields_.end()) out.fields_[n] = it->second;
  }
  return out;
}

ParticleData ParticleData::select(const std::vector<std::string>& wanted) && {
  ParticleData out;
  out.ids = std::move(ids);
  for (const auto& n : wanted) {
    auto it = fields_.find(n);
    if (it != fields_.end()) out.fields_[n] = std::move(it->second);
  }
  fields_.clear();
  ids.clear();
  return out;
}

std::map<std::int64_t, std::size_t> ParticleData::index() const {
  std::map<std::int64_t, std::size_t> m;
  for (std::size_t i = 0; i < ids.size(); ++i) m.emplace(ids[i], i);
  return m;
}

}  // namespace cosim::link
