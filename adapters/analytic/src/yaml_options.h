// Reading an adapter's options (Welcome.config_yaml) with errors that name the option.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <stdexcept>
#include <string>

namespace cosim::analytic {

class Options {
 public:
  Options(const std::string& yaml, std::string owner) : owner_(std::move(owner)) {
    try {
      root_ = YAML::Load(yaml);
    } catch (const YAML::Exception& e) {
      throw std::runtime_error(owner_ + ": options are not valid YAML: " + e.what());
    }
    if (root_.IsNull()) root_ = YAML::Node(YAML::NodeType::Map);
  }
  const YAML::Node& root() const { return root_; }
  bool has(const std::string& k) const { return static_cast<bool>(root_[k]); }

  double number(const std::string& k, double fallback) const {
    return has(k) ? number(root_[k], k) : fallback;
  }
  double number(const YAML::Node& n, const std::string& k) const {
    try {
      return n.as<double>();
    } catch (const YAML::Exception&) {
      throw std::runtime_error(owner_ + ": option '" + k + "' must be a number");
    }
  }
  double positive(const std::string& k, double fallback) const {
    double v = number(k, fallback);
    if (!(v > 0)) throw std::runtime_error(owner_ + ": option '" + k + "' must be > 0");
    return v;
  }
  std::array<double, 3> vec(const YAML::Node& n, const std::string& k) const {
    if (!n.IsSequence() || n.size() != 3) {
      throw std::runtime_error(owner_ + ": option '" + k + "' must be three numbers [x, y, z]");
    }
    return {number(n[0], k), number(n[1], k), number(n[2], k)};
  }
  std::array<double, 3> vec(const std::string& k, std::array<double, 3> fallback) const {
    return has(k) ? vec(root_[k], k) : fallback;
  }
  std::string text(const std::string& k, const std::string& fallback) const {
    return has(k) ? root_[k].as<std::string>() : fallback;
  }
  bool flag(const std::string& k, bool fallback) const {
    if (!has(k)) return fallback;
    try {
      return root_[k].as<bool>();
    } catch (const YAML::Exception&) {
      throw std::runtime_error(owner_ + ": option '" + k + "' must be true or false");
    }
  }
  void allowOnly(std::initializer_list<const char*> keys) const {
    for (const auto& kv : root_) {
      const auto k = kv.first.as<std::string>();
      bool ok = false;
      std::string list;
      for (const char* a : keys) {
        ok = ok || k == a;
        list += (list.empty() ? "" : ", ") + std::string(a);
      }
      if (!ok)
        throw std::runtime_error(owner_ + ": unknown option '" + k + "' (known: " + list + ")");
    }
  }

 private:
  YAML::Node root_;
  std::string owner_;
};

}  // namespace cosim::analytic
