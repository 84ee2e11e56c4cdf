// Real contact onsets for bench/contact_integrators.cpp: the reference solves a scenario once, keeping every
// free flight's start; each contact's onset state is then the closed-form free flight (reference/free_flight.h)
// from the start before it to the onset time the reference located. Every stepper then starts from the same
// state the reference's own Dormand-Prince started from (to the rounding of one closed-form advance).
#pragma once

#include <string>
#include <vector>

#include "bench/contact_phase_steppers.h"
#include "model/trajectory.h"
#include "physics/modal_model.h"

namespace ib::bench {

struct CaseContacts {
  ModalModel model;
  double max_step_s = 0;                       // the reference's scan grid step, its contact phases' largest step
  std::vector<ContactOnset> onsets;            // the chosen contacts
  std::vector<ContactEvent> reference_events;  // the reference's record of the same contacts
  int contacts_in_run = 0;                     // all of the run's contact episodes
  double worst_onset_indentation_m = 0;        // max |delta| at the rebuilt onsets: ~0 when they are right
  double largest_onset_shift_s = 0;            // max |rebuilt onset - the reference's onset time|
};

// At most max_contacts of the run's contacts, evenly spread over it (all when it has no more).
CaseContacts contacts_of(const std::string& scenario_path, ContactLaw law, int max_contacts);

}  // namespace ib::bench
