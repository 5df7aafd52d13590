// Stub until the HDF5 recording lands.
#include "outcome_record.hpp"

namespace collide2d::properties {

void record_property_outcome(const PropertyOutcome&) {}

}  // namespace collide2d::properties
