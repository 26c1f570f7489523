// Parameters of one model as given in the scenario, with getters whose errors name the model
// and the parameter.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace cosim::models {

// Not a cosim::Error: the plugin interface (models/include) stands alone, so that a plugin builds
// with -I models/include only. Where cosim meets it, it takes the kind of what it was doing:
// an input error while the scenario's models are built, a solver error during a run (the
// fields a law was given came from a solver).
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Parameters {
 public:
  Parameters() = default;
  explicit Parameters(std::string owner) : owner_(std::move(owner)) {}

  void set(const std::string& key, double v) { numbers_[key] = v; }
  void setText(const std::string& key, const std::string& v) { texts_[key] = v; }
  void setList(const std::string& key, std::vector<double> v) { lists_[key] = std::move(v); }
  void setChild(const std::string& key, std::vector<Parameters> v) {
    children_[key] = std::move(v);
  }

  bool has(const std::string& key) const;
  double number(const std::string& key) const;                   // required
  double number(const std::string& key, double fallback) const;  // optional
  // Required, checked lo <= v <= hi (use +-inf for open ends); error names model + key + range.
  double number(const std::string& key, double lo, double hi) const;
  double positive(const std::string& key) const;
  double positive(const std::string& key, double fallback) const;
  std::string text(const std::string& key) const;
  std::string text(const std::string& key, const std::string& fallback) const;
  std::vector<double> list(const std::string& key, std::size_t expected_size) const;
  const std::vector<Parameters>& children(const std::string& key) const;
  // Optional on/off switch: text true/false/yes/no/on/off or number 1/0; anything else is an
  // error naming the model and the key.
  bool flag(const std::string& key, bool fallback) const;
  // A copy without `key` (e.g. the `shape` selector of a union part) and with a new owner name.
  Parameters without(const std::string& key, std::string new_owner) const;

  const std::string& owner() const { return owner_; }
  // Every value, by kind (to carry them elsewhere whole, e.g. cosim/link/models_wire.h).
  const std::map<std::string, double>& numbers() const { return numbers_; }
  const std::map<std::string, std::string>& texts() const { return texts_; }
  const std::map<std::string, std::vector<double>>& lists() const { return lists_; }
  const std::map<std::string, std::vector<Parameters>>& allChildren() const { return children_; }
  std::vector<std::string> keys() const;
  // Throws if a key not in `known` was given (catches typos like "cg_facter").
  void rejectUnknown(const std::vector<std::string>& known) const;

 private:
  std::string owner_;
  std::map<std::string, double> numbers_;
  std::map<std::string, std::string> texts_;
  std::map<std::string, std::vector<double>> lists_;
  std::map<std::string, std::vector<Parameters>> children_;
};

}  // namespace cosim::models
