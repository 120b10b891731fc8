// Light and shadow linking (Blender 4.0+, Cycles' light sets): an emitter (a lamp, or an object
// with an emitting material) lights only the receivers of its light sets and is shadowed only by
// the blockers of its shadow sets.
//
// Receivers and blockers come in at most 64 sets each (the add-on builds them from the emitters'
// receiver and blocker collections, as Blender's depsgraph does): every object names its receiver
// set and its blocker set (0: the default set, of objects no collection mentions); every emitter
// keeps one entry of the scene's EmitterLinks table, the bit masks of the receiver sets it lights
// and of the blocker sets that cast its shadows (entry 0: every set, an emitter linked to nothing).
//
// Where the sets apply (the path tracer): next-event estimation still chooses lights as it always
// does, so the forward hit's MIS weight stays that choice's, and a light the receiver is not in
// the sets of then brings nothing; a BSDF-sampled ray leaving a receiver sees only the emitters
// lighting it (a camera ray sees them all); the shadow ray towards an emitter with shadow sets
// passes what is not one of its blockers. Such a shadow-linked emitter is found by next-event
// estimation alone at vertices NEE can sample (its MIS weight 1, its forward hits there not
// counted), as a BSDF-sampled ray towards it could be stopped by a non-blocker; Cycles instead
// traces an extra ray past the non-blockers (its dedicated shadow-linking light). Delta lobes,
// which NEE cannot sample, see it by their ray, and past the surfaces that ray meets that are
// none of its blockers (the path tracer's shadow_linked_behind, Lights::shadow_linked_along_ray).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace torrance {

constexpr uint64_t kAllLinkSets = ~uint64_t(0);
constexpr int kMaxLinkSets = 64;

struct EmitterLinks {
  uint64_t light_sets = kAllLinkSets;   // bit s: lights the receivers of set s
  uint64_t shadow_sets = kAllLinkSets;  // bit s: shadowed by the blockers of set s
};

class LightLinks {
 public:
  // Entries 1..table.size() of the table (entry 0 stays the unlinked emitter's).
  void set(const std::vector<EmitterLinks>& table) {
    if (table.size() > 254) throw std::invalid_argument("at most 254 light linking entries");
    table_.assign(1, EmitterLinks{});
    table_.insert(table_.end(), table.begin(), table.end());
    if (table.empty()) table_.clear();
  }
  // Whether the scene links anything (else every query below is true / false as unlinked).
  bool any() const { return !table_.empty(); }
  size_t size() const { return table_.empty() ? 1 : table_.size(); }
  static uint8_t checked_entry(int entry, size_t size) {
    if (entry < 0 || size_t(entry) >= size)
      throw std::invalid_argument("light linking entry " + std::to_string(entry) + " does not exist");
    return uint8_t(entry);
  }
  static uint8_t checked_set(int set) {
    if (set < 0 || set >= kMaxLinkSets)
      throw std::invalid_argument("light linking set " + std::to_string(set) + " is not in [0, 63]");
    return uint8_t(set);
  }
  // An entry past the table's end (an object named one the table never got) is unlinked.
  bool lights(uint8_t entry, uint8_t receiver_set) const {
    return entry >= table_.size() || (table_[entry].light_sets >> (receiver_set & 63u)) & 1u;
  }
  bool shadow_linked(uint8_t entry) const { return shadow_sets(entry) != kAllLinkSets; }
  // Whether some shadow-linked entry's shadow sets leave out every blocker set in `passed` (bit
  // s: set s), i.e. its emitter is still seen past surfaces of those sets.
  bool shadow_linked_past(uint64_t passed) const {
    for (size_t e = 1; e < table_.size(); ++e)
      if (table_[e].shadow_sets != kAllLinkSets && !(table_[e].shadow_sets & passed)) return true;
    return false;
  }
  uint64_t shadow_sets(uint8_t entry) const { return entry < table_.size() ? table_[entry].shadow_sets : kAllLinkSets; }

 private:
  std::vector<EmitterLinks> table_;  // empty: no linking in the scene
};

// Whether an object of blocker set `blocker_set` casts the shadows of an emitter of these shadow sets.
inline bool blocks_shadow(uint64_t shadow_sets, uint8_t blocker_set) {
  return (shadow_sets >> (blocker_set & 63u)) & 1u;
}

}  // namespace torrance
