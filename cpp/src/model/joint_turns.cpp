// Counting the turns of spatial joints in a run (joint_turns.hpp).
#include "lagmb/model/joint_turns.hpp"

#include <cmath>

#include "lagmb/model/model.hpp"
#include "lagmb/space.hpp"

namespace lagmb {

const TurnCounter* count_turns(const Model& model, const double* q, const double* v, double h, double* state) {
  const TurnCounter* jumped = nullptr;
  for (const TurnCounter& c : model.turn_counters()) {
    double* shift = state + c.run_state;  // [0]: the angle at the last step - center, [1]: its rate there
    const spatial::Loc cq = gather_q<Spatial>(q, c.where), cv = gather_v<14>(v, c.where);
    const double before = c.reading.center + shift[0];
    const spatial::ScalarTerm s = c.reading.read(cq, {}, before);
    const double rate = s.gradient.dot(cv);
    // the whole turns the rates say the joint made beyond the reading
    const double expected = before + 0.5 * h * (shift[1] + rate);
    const double angle = s.value + 2.0 * kPi * std::round((expected - s.value) / (2.0 * kPi));
    if (c.read && !jumped && !(std::abs(angle - before) < kPi)) jumped = &c;
    shift[0] = angle - c.reading.center;
    shift[1] = rate;
  }
  return jumped;
}

}  // namespace lagmb
