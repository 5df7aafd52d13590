#include "property_case.hpp"

namespace collide2d::properties {

std::optional<FailingScene>& last_failing_scene() {
  thread_local std::optional<FailingScene> scene;
  return scene;
}

}  // namespace collide2d::properties
