// Model registry: built-in laws register themselves by name; plugins (shared libraries built
// outside the tree) add theirs through the C entry point cosim_register_models(Registry&).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cosim/models/model.h"

namespace cosim::models {

class Registry {
 public:
  template <class T>
  using Factory = std::function<std::unique_ptr<T>(const Parameters&)>;

  static Registry& instance();

  // Register a factory under a name (a later registration of the same name replaces the
  // earlier one, so a plugin may override a built-in). Inline so that plugins need no symbol
  // from the host executable to register.
  void addDrag(const std::string& name, Factory<DragLaw> f) { drag_[name] = std::move(f); }
  void addForce(const std::string& name, Factory<ForceModel> f) { force_[name] = std::move(f); }
  void addMassTransfer(const std::string& name, Factory<MassTransferLaw> f) {
    mass_[name] = std::move(f);
  }
  void addZone(const std::string& name, Factory<CoatingZone> f) { zone_[name] = std::move(f); }

  // Throw ModelError("unknown drag law 'x'; known: a, b, c") for unknown names.
  std::unique_ptr<DragLaw> makeDrag(const std::string& name, const Parameters& p) const;
  std::unique_ptr<ForceModel> makeForce(const std::string& name, const Parameters& p) const;
  std::unique_ptr<MassTransferLaw> makeMassTransfer(const std::string& name,
                                                    const Parameters& p) const;
  std::unique_ptr<CoatingZone> makeZone(const std::string& name, const Parameters& p) const;

  std::vector<std::string> dragNames() const;
  std::vector<std::string> forceNames() const;
  std::vector<std::string> massTransferNames() const;
  std::vector<std::string> zoneNames() const;

  // dlopen a plugin and call its cosim_register_models. Throws ModelError with dlerror().
  void loadPlugin(const std::string& path);

 private:
  Registry();
  std::map<std::string, Factory<DragLaw>> drag_;
  std::map<std::string, Factory<ForceModel>> force_;
  std::map<std::string, Factory<MassTransferLaw>> mass_;
  std::map<std::string, Factory<CoatingZone>> zone_;
};

}  // namespace cosim::models

// A plugin defines this function (extern "C") and registers its models in it.
extern "C" void cosim_register_models(cosim::models::Registry& registry);
