// Union of coating zones. Parameter: parts (list of zones; each part names its `shape` and that
// shape's parameters; parts may themselves be unions). Inside: inside any part.
#pragma once

#include <memory>
#include <vector>

#include "cosim/models/model.h"

namespace cosim::models {

class UnionZone final : public CoatingZone {
 public:
  explicit UnionZone(const Parameters& p);  // builds each part by name through the Registry
  std::string name() const override { return "union"; }
  bool contains(const double* x) const override;
  std::size_t size() const { return parts_.size(); }

 private:
  std::vector<std::unique_ptr<CoatingZone>> parts_;
};

}  // namespace cosim::models
