// The instrument registry (instrument.h) and an instrument block's items.
// Guarantees: every item an instrument makes has an id "<block>.<sub>", its
// block's `when`, and a registered type.
#include <stdexcept>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {

std::span<const Instrument* const> instruments() {
  static const std::vector<const Instrument*> all = {&instrument_nasa_tlx(), &instrument_sus(), &instrument_ssq()};
  return all;
}

const Instrument* find_instrument(std::string_view name) {
  for (const Instrument* i : instruments())
    if (i->name == name) return i;
  return nullptr;
}

std::vector<Item> instrument_items(const InstrumentUse& use) {
  if (!use.instrument) throw std::invalid_argument("instrument block '" + use.id + "' names no instrument");
  std::vector<Item> out = use.instrument->items(use.keys);
  for (Item& it : out) {
    if (!it.type) throw std::logic_error("instrument " + use.instrument->name + ": item '" + it.sub + "' has no registered type");
    it.id = use.id + "." + it.sub;
    it.when = use.when;
    it.instrument = use.instrument;
    it.block = use.id;
  }
  return out;
}

}  // namespace dtlab::questionnaire
