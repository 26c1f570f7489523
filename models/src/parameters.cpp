#include "cosim/models/parameters.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace cosim::models {

bool Parameters::has(const std::string& k) const {
  return numbers_.count(k) || texts_.count(k) || lists_.count(k) || children_.count(k);
}

double Parameters::number(const std::string& k) const {
  auto it = numbers_.find(k);
  if (it == numbers_.end()) {
    if (texts_.count(k)) {
      throw ModelError(owner_ + ": parameter '" + k + "' must be a number, got '" + texts_.at(k) +
                       "'");
    }
    throw ModelError(owner_ + ": missing parameter '" + k + "'");
  }
  if (!std::isfinite(it->second)) {
    throw ModelError(owner_ + ": parameter '" + k + "' must be finite");
  }
  return it->second;
}

double Parameters::number(const std::string& k, double fallback) const {
  return has(k) ? number(k) : fallback;
}

double Parameters::number(const std::string& k, double lo, double hi) const {
  double v = number(k);
  if (v < lo || v > hi) {
    throw ModelError(fmt::format("{}: parameter '{}' = {:.6g} is out of range [{:.6g}, {:.6g}]",
                                 owner_, k, v, lo, hi));
  }
  return v;
}

double Parameters::positive(const std::string& k) const {
  double v = number(k);
  if (!(v > 0.0)) {
    throw ModelError(fmt::format("{}: parameter '{}' = {:.6g} must be > 0", owner_, k, v));
  }
  return v;
}

double Parameters::positive(const std::string& k, double fallback) const {
  return has(k) ? positive(k) : fallback;
}

std::string Parameters::text(const std::string& k) const {
  auto it = texts_.find(k);
  if (it == texts_.end()) throw ModelError(owner_ + ": missing parameter '" + k + "'");
  return it->second;
}

std::string Parameters::text(const std::string& k, const std::string& fallback) const {
  return texts_.count(k) ? texts_.at(k) : fallback;
}

std::vector<double> Parameters::list(const std::string& k, std::size_t n) const {
  auto it = lists_.find(k);
  if (it == lists_.end()) throw ModelError(owner_ + ": missing parameter '" + k + "'");
  if (n != 0 && it->second.size() != n) {
    throw ModelError(owner_ + ": parameter '" + k + "' must have " + std::to_string(n) +
                     " numbers, got " + std::to_string(it->second.size()));
  }
  return it->second;
}

const std::vector<Parameters>& Parameters::children(const std::string& k) const {
  auto it = children_.find(k);
  if (it == children_.end()) throw ModelError(owner_ + ": missing parameter '" + k + "'");
  return it->second;
}

bool Parameters::flag(const std::string& k, bool fallback) const {
  if (!has(k)) return fallback;
  if (auto it = numbers_.find(k); it != numbers_.end()) {
    if (it->second == 1.0) return true;
    if (it->second == 0.0) return false;
  } else if (auto t = texts_.find(k); t != texts_.end()) {
    std::string v = t->second;
    std::transform(v.begin(), v.end(), v.begin(),
                   [](unsigned char ch) { return std::tolower(ch); });
    if (v == "true" || v == "yes" || v == "on" || v == "1") return true;
    if (v == "false" || v == "no" || v == "off" || v == "0") return false;
  }
  throw ModelError(owner_ + ": parameter '" + k + "' must be true or false");
}

Parameters Parameters::without(const std::string& k, std::string new_owner) const {
  Parameters copy = *this;
  copy.owner_ = std::move(new_owner);
  copy.numbers_.erase(k);
  copy.texts_.erase(k);
  copy.lists_.erase(k);
  copy.children_.erase(k);
  return copy;
}

std::vector<std::string> Parameters::keys() const {
  std::vector<std::string> v;
  for (const auto& [k, x] : numbers_) v.push_back(k);
  for (const auto& [k, x] : texts_) v.push_back(k);
  for (const auto& [k, x] : lists_) v.push_back(k);
  for (const auto& [k, x] : children_) v.push_back(k);
  std::sort(v.begin(), v.end());
  return v;
}

void Parameters::rejectUnknown(const std::vector<std::string>& known) const {
  for (const auto& k : keys()) {
    if (std::find(known.begin(), known.end(), k) == known.end()) {
      std::string list;
      for (const auto& q : known) list += (list.empty() ? "" : ", ") + q;
      throw ModelError(owner_ + ": unknown parameter '" + k +
                       "' (known: " + (list.empty() ? "none" : list) + ")");
    }
  }
}

}  // namespace cosim::models
