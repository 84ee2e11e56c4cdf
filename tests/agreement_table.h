// THE agreement table (issue 8): per engine, published case and law, the step, the contact path and its
// options, and the tolerances against the reference on the engine's own chain and against the beam, each
// with why; and how long each case runs. tests/agreement_test.cpp runs it (its header says how the
// metrics are compared). An engine of the build without its rows fails AgreementTable.OneRowPerEngineCaseAndLaw.
#pragma once

#include <limits>

#include "model/scenario.h"

namespace ib {

constexpr double kNotApplicable = std::numeric_limits<double>::quiet_NaN();

// How long each case runs in the test, and the scoring window (its last window_s). The reference's
// window statistics were measured at these lengths against the published 100 s / 14 s (K = 8 chain
// and beam, every law; tests print them again): see each row.
struct RunLength {
  const char* scenario;
  double duration_s;  // simulated time [s]
  double window_s;    // scoring window: the last window_s of the run [s]
  const char* why;
  // No impact in the reference under any law: the law cannot act, so the case is checked with Hertz alone
  // (the engine's chain, motor and damping; AgreementTable.ACaseWithoutContactHasNoImpactUnderAnyLaw shows
  // the premise). The full study runs it with Hertz alone too (docs/studies.md).
  bool without_contact = false;
};
constexpr RunLength kRunLengths[] = {
    {"resonance", 20, 10,
     "settles within 10 s into one impact every second motor cycle; chain reference, [10, 20] s against [86, 100] s "
     "of 100 s: 0.4892 / 0.4933 impacts per cycle, frame 1 sensor peak -0.0 % (spring-dashpot), +0.1 % (Hertz), "
     "0.0 % (Newton), mean contact duration 0.0 %"},
    {"pre_resonance", 20, 10,
     "steady by 10 s: 0.3332 / 0.3354 impacts per cycle, frame 1 sensor peak within 0.2 %, contact duration within "
     "1e-6 of the 100 s run's (chain reference, every law)"},
    {"post_resonance", 50, 14,
     "no impacts; frame 1's peak is the forced response plus the start-up transient, which decays with "
     "zeta omega_1 = 0.13 1/s: at 50 s the peak is 0.6 % above the 100 s run's (0.1252 g vs 0.1245 g), at 30 s 8 %",
     true},
    {"free_vibration", 4, 4,
     "the whole run is the window; every reference impact comes before 2.6 s (beam and chain, every law), so 4 s "
     "holds all of them and the metrics are those of the published 14 s"},
};

struct Tolerances {
  double impacts_per_cycle;  // largest |run - reference| [impacts per motor cycle]; kNotApplicable: no such metric
  double sensor_peak;        // largest |run / reference - 1| of frame 1's sensor peak [-]
  double contact_duration;   // largest |run / reference - 1| of the mean contact duration [-]; kNotApplicable: none
};

struct AgreementRow {
  const char* engine;    // simulator name, as the registry knows it
  const char* scenario;  // scenarios/paper/<scenario>.toml
  ContactLaw law;
  double time_step_s;        // the engine's fixed step [s]
  const char* contact_path;  // option contact=
  const char* options;       // further engine options, "name=value" or "" (a named configuration, see why)
  Tolerances chain;          // against the reference on the engine's own K-link chain
  Tolerances beam;           // against the continuous-beam reference (chain tolerance + the chain's model gap)
  const char* why;           // why these tolerances at this step
};

constexpr ContactLaw kHertz = ContactLaw::hertz, kSpringDashpot = ContactLaw::viscoelastic,
                     kNewton = ContactLaw::newton;
constexpr double na = kNotApplicable;

// Tolerances from the physics, then checked against the measured errors (README "Agreement with the
// reference" has both side by side):
// - impacts per cycle, forced cases: 0.03 per cycle = 2 impacts in the 10 s window (66 to 70 motor
//   cycles): the regime (one impact every second cycle at resonance, one in three before it) must be the
//   reference's; a window edge can cut the pattern one impact differently on either side. The K = 8 chain
//   and the beam differ by one impact at resonance with Hertz, so the beam gets the same 0.03.
//   Post-resonance: 0 (no impacts in the reference; any impact is a different regime).
// - frame 1's sensor peak: 5 % where the step resolves the contact: the peak is the largest velocity change
//   over a 0.49 ms sensor window, about (1 + e) times the approach speed, so a restitution error of up to
//   7 % (backward-Euler contacts at 1e-5 s) moves it by up to 4 %; the maximum over 20 to 35 impacts
//   averages the sensor-window phase. Beam: plus the chain's own gap to the beam at these windows
//   (resonance 7 to 9 %, pre-resonance 2 to 4 %, free vibration 1 to 2 %, post-resonance 1.3 %).
// - mean contact duration: 5 %: an engine's episode is a whole number of steps (+-h/2 per impact, averaged
//   over >= 8 impacts: <= 2 % at tau/h = 6, less at finer steps) plus the contact integration error (about
//   1 % where the contact spans >= 12 steps). Beam: Hertz plus 2 % (the chain's tip effective mass moves the
//   contact time by 1 to 1.5 %); spring-dashpot plus 5 %, because the beam reference runs the published law,
//   whose tensile tail makes its contacts 4 % (c/k = 24 us) longer than any engine's compressive contact.
constexpr const char* kHertzStep =
    "Hertz is a force from the tip states (MuJoCo, ODE, Bullet and DART have no nonlinear contact), explicit: its "
    "0.25 ms contact stiffens to 18000 rad/s and gains energy at 1e-4 s (e > 1). At 2e-5 s (12 steps per contact, "
    "as ODE's and Simbody's Hertz) every metric of the forced cases is within 1.4 % of the chain reference (frame 1's "
    "peak -0.6 % in MuJoCo and Bullet, +0.8 % in DART at resonance), so 2e-5 s";
constexpr const char* kOdeHertzStep =
    "Hertz as a force from the tip states; ODE's implicit hinge springs keep 2e-5 s (12 steps per contact) within "
    "1.3 % of the chain reference, so the smaller 1e-5 s is not needed in the forced cases";
constexpr const char* kMujocoSpringDashpot =
    "MuJoCo's own contact from solref/solimp at the default 1e-4 s (6 steps per 0.6 ms contact): restitution "
    "within 1 % of the clipped law, so the default step meets 5 %";
constexpr const char* kImplicitSpringDashpot =
    "the soft contact is a backward-Euler spring-dashpot, losing about pi omega h / 2 of the restitution "
    "(omega = 5200 rad/s): at the default step (ODE 1e-4 s: -40 %, Bullet 5e-5 s: -30 %) the peak is 9 % low "
    "before resonance and ODE changes regime, so 1e-5 s (-7 %; ODE 2e-5 s gives -4.6 %, Bullet 5e-5 s -9.0 % "
    "pre-resonance), where 5 % holds";
constexpr const char* kMujocoNewton =
    "MuJoCo has no restitution: a no-tension spring-dashpot lasting 4 steps (0.4 ms at the default 1e-4 s) "
    "that rebounds with e; an impulse spread over most of a 0.49 ms sensor window reads 2 to 4 % low, inside 5 %";
constexpr const char* kMujocoNewtonPreResonance =
    "as kMujocoNewton, but in the pre-resonance on the tuned chain (rig.md section 4) the 0.4 ms stand-in contact at "
    "1e-4 s reads frame 1's sensor peak 5.8 % low against the chain reference; at 5e-5 s (0.2 ms) +0.7 %, at 2e-5 s "
    "+1.7 %: so 5e-5 s";
constexpr const char* kOdeNewton =
    "dContactBounce is exact per impact but found at the start of the step that begins overlapping, up to one "
    "step late: at the default 1e-4 s the peak is 3.7 % / 7.2 % low (resonance / pre-resonance), at 2e-5 s "
    "within 2 %, so 2e-5 s";
constexpr const char* kBulletNewton =
    "restitution with threshold 0 and no push-out: e within 0.2 % at the default 5e-5 s, exact impulse";
constexpr const char* kPostResonance =
    "no impacts in the reference (tip amplitude 0.46 mm below the 1 mm gap): the forced response of the chain "
    "alone at the engine's default step; peak within 2 % (the chain's frequencies are exact to 1e-5; ODE's implicit "
    "hinge springs add omega h / 2 to zeta, which shortens the start-up transient: measured -0.6 %)";
constexpr const char* kFreeVibration =
    "free vibration at 1e-5 s for every law (4 s runs are cheap); the largest sensor reading is the first "
    "impact's (t = 0.048 s, before any drift; chain reference: Hertz 11.69 g, Newton 10.64 g both from it), so 5 %";
constexpr const char* kFreeVibrationSpringDashpot =
    "finding: frame 1's sensor peak in free vibration is a phase-sampled statistic of a few impacts. With the "
    "0.6 ms spring-dashpot contact (longer than the 0.49 ms sensor window) the peak comes from a later impact "
    "(chain reference: the first impact alone reads 7.33 g, the whole run 8.11 g), and where it falls on the 2048 Hz "
    "grid decides it: a 0.4 % change of the sensor rate moves the reference's "
    "own value by -30 % to +19 %. Engines whose later impacts drift by tens of us land anywhere in that range, "
    "and a smaller step does not help (ODE -6.6 % at 1e-5 s, -10.3 % at 2e-6 s; Bullet +4.0 % at 1e-5 s, -9.3 % "
    "at 5e-6 s). On the tuned chain (rig.md section 4) Bullet reads -17.7 % (chain) and -25.7 % (beam), DART -16.4 % "
    "(beam): the bounds 25 % (chain) and 30 % (beam) are the reference's own range, not a convergence check; the "
    "row's contact duration is one";
constexpr const char* kImplicitJointSpringsPreResonance =
    "finding: ODE's and DART's implicit joint springs add omega h / 2 to every mode's zeta, and on the tuned chain "
    "(rig.md section 4: mode 2 at the beam's 73.19 Hz, near a harmonic of the impacts) that changes the mode-2 "
    "ringing frame 1's sensor reads by +5 to +9 % against the chain reference, first order in the step: ODE, Hertz, "
    "+7.6 % at 2e-5 s (DART the same), +5.5 % at 1e-5 s, +3.9 % at 5e-6 s, +1.6 % at 2.5e-6 s; with explicit springs "
    "(no such damping) -0.3 % at 1e-5 s. So 10 % (chain) and 12 % (beam)";

constexpr const char* kDartSpringDashpot =
    "DART has no compliant rigid contact: the law's force from the tip states (matched = injected), explicit; at "
    "5e-5 s (12 steps per 0.6 ms contact) the restitution is within 0.5 % of the law's, so 5 %; the force is the "
    "published law's, tensile tail included (the chain reference here clips it): contacts up to 3 % longer";
constexpr const char* kDartNewton =
    "named configuration length_unit=cm: in metres DART's bounce threshold (no bounce when e v <= 0.1 m/s) makes "
    "every impact of the rig plastic (e = 0.003 at resonance: a finding, tests/dart_single_impact_test.cpp); in "
    "centimetres the same physics bounces with e within 0.3 %. Rigid contact found up to one step late (as ODE's), "
    "so 2e-5 s";

constexpr const char* kSimbodyHertz =
    "Simbody's own Hunt-Crossley contact with the mapped material (equal to the law to 1e-9 on the posed rig, "
    "tests/simbody_contact_mapping_test.cpp), a force that semi-explicit Euler integrates explicitly like the "
    "injected ones. In the forced cases 2e-5 s (12 steps per 0.25 ms contact) keeps every metric within 1.3 % of "
    "the chain reference (as ODE's Hertz at 2e-5 s), at half the cost of 1e-5 s; the free vibration, whose peak is "
    "its first impact's, at 1e-5 s as for the other engines' Hertz";
constexpr const char* kSimbodySpringDashpot =
    "the law as a Simbody force element at the default 5e-5 s (12 steps per 0.6 ms contact, omega h = 0.26): "
    "explicit, restitution within 1 % of the law's, so 5 %. The element is the scenario's published law, tensile "
    "tail included, while the chain reference here runs it clipped: contacts 2 to 4 % longer than the chain's, "
    "within 2 % of the beam's (unclipped) ones";
constexpr const char* kSimbodyNewton =
    "Simbody's rigid contact (SemiExplicitEulerTimeStepper, Newton restitution, constraint tolerance 1e-6 m): "
    "the impact is found in the step that closes the gap, up to one step late (as ODE's), so 2e-5 s";
constexpr const char* kSiconosNewton =
    "Siconos's NewtonImpactNSL under Moreau-Jean: the impact is exact in the velocities of the step that closes the "
    "predicted gap (e of the step's relative velocity, tests/siconos_moreau_jean_test.cpp), its time first order in "
    "the step (up to one step late): frame 1's peak +3.0 % (resonance) and -0.7 % (pre-resonance) at the default "
    "1e-4 s, +0.2 % and -0.1 % at 5e-5 s (+0.4 % and +0.1 % at 2e-5 s: chaotic at that level), so 5e-5 s";
constexpr const char* kSiconosHertz =
    "Hertz as a smooth internal force of the system, integrated by Moreau-Jean's theta = 1/2 (the trapezoidal rule) "
    "with its Newton loop: 5e-5 s spans the 0.25 ms contact in 5 steps (at 1e-4 s frame 1's peak is +6 % and the "
    "contact +12 % at resonance). The trapezoidal rule lengthens an oscillation's period by (omega h)^2 / 12: 6.7 % "
    "at the contact's peak stiffness (18 000 rad/s), less over the softer start and end, so the contact duration "
    "gets 7 % (measured +2.6 and +4.2 %), the beam 2 % more";
constexpr const char* kSiconosSpringDashpot =
    "the published spring-dashpot as a smooth internal force (its tensile tail included, as DART's and Simbody's: "
    "contacts about 4 % longer than the clipped chain reference's), the trapezoidal rule at 5e-5 s (omega h = 0.26: "
    "a period 0.6 % long), an episode counted in whole steps (up to h / 2 tau = 4 % over the 0.6 ms contact): "
    "contact duration 10 % against the chain (measured +5.1 and +6.7 %) and the beam (+1.1 and +2.2 %)";
constexpr const char* kSiconosPostResonance =
    "as kPostResonance at Siconos's default 1e-4 s: the chain is linear and Moreau-Jean's theta = 1/2 is "
    "unconditionally stable and adds no damping. No impact happens, so the law never acts: the injected path runs "
    "the linear system (9 us a step) rather than the smooth force's Newton loop (25 to 30 us), the same motion";
constexpr const char* kSimbodyPostResonance =
    "as kPostResonance at Simbody's default 5e-5 s: the hinge springs are explicit forces in Simbody and "
    "semi-explicit Euler is stable only below 7.5e-5 s on the K = 8 chain, so 1e-4 s diverges (a finding)";

// THE table: engine, case, law, step [s], contact path, tolerances {impacts per cycle, sensor peak, contact
// duration} against the chain reference, then against the beam reference, and why.
constexpr AgreementRow kAgreement[] = {
    // ---------------------------------------------------------------- MuJoCo 2.2.2, semi-implicit Euler
    {"mujoco", "resonance", kHertz, 2e-5, "matched", "", {0.03, 0.05, 0.05}, {0.03, 0.15, 0.07}, kHertzStep},
    {"mujoco",
     "resonance",
     kSpringDashpot,
     1e-4,
     "matched",
     "",
     {0.03, 0.05, 0.05},
     {0.03, 0.15, 0.10},
     kMujocoSpringDashpot},
    {"mujoco", "resonance", kNewton, 1e-4, "matched", "", {0.03, 0.05, na}, {0.03, 0.15, na}, kMujocoNewton},
    {"mujoco", "pre_resonance", kHertz, 2e-5, "matched", "", {0.03, 0.05, 0.05}, {0.03, 0.10, 0.07}, kHertzStep},
    {"mujoco",
     "pre_resonance",
     kSpringDashpot,
     1e-4,
     "matched",
     "",
     {0.03, 0.05, 0.05},
     {0.03, 0.10, 0.10},
     kMujocoSpringDashpot},
    {"mujoco",
     "pre_resonance",
     kNewton,
     5e-5,
     "matched",
     "",
     {0.03, 0.05, na},
     {0.03, 0.10, na},
     kMujocoNewtonPreResonance},
    {"mujoco", "post_resonance", kHertz, 1e-4, "matched", "", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"mujoco", "free_vibration", kHertz, 1e-5, "matched", "", {na, 0.05, 0.05}, {na, 0.10, 0.07}, kFreeVibration},
    {"mujoco",
     "free_vibration",
     kSpringDashpot,
     1e-5,
     "matched",
     "",
     {na, 0.25, 0.05},
     {na, 0.30, 0.10},
     kFreeVibrationSpringDashpot},
    {"mujoco", "free_vibration", kNewton, 1e-5, "matched", "", {na, 0.05, na}, {na, 0.10, na}, kFreeVibration},
    // ---------------------------------------------------------------- ODE 0.16.2, dWorldStep, implicit hinge springs
    {"ode", "resonance", kHertz, 2e-5, "matched", "", {0.03, 0.05, 0.05}, {0.03, 0.15, 0.07}, kOdeHertzStep},
    {"ode",
     "resonance",
     kSpringDashpot,
     1e-5,
     "matched",
     "",
     {0.03, 0.05, 0.05},
     {0.03, 0.15, 0.10},
     kImplicitSpringDashpot},
    {"ode", "resonance", kNewton, 2e-5, "matched", "", {0.03, 0.05, na}, {0.03, 0.15, na}, kOdeNewton},
    {"ode",
     "pre_resonance",
     kHertz,
     2e-5,
     "matched",
     "",
     {0.03, 0.10, 0.05},
     {0.03, 0.12, 0.07},
     kImplicitJointSpringsPreResonance},
    {"ode",
     "pre_resonance",
     kSpringDashpot,
     1e-5,
     "matched",
     "",
     {0.03, 0.05, 0.05},
     {0.03, 0.10, 0.10},
     kImplicitSpringDashpot},
    {"ode",
     "pre_resonance",
     kNewton,
     2e-5,
     "matched",
     "",
     {0.03, 0.10, na},
     {0.03, 0.12, na},
     kImplicitJointSpringsPreResonance},
    {"ode", "post_resonance", kHertz, 1e-4, "matched", "", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"ode", "free_vibration", kHertz, 1e-5, "matched", "", {na, 0.05, 0.05}, {na, 0.10, 0.07}, kFreeVibration},
    {"ode",
     "free_vibration",
     kSpringDashpot,
     1e-5,
     "matched",
     "",
     {na, 0.25, 0.05},
     {na, 0.30, 0.10},
     kFreeVibrationSpringDashpot},
    {"ode", "free_vibration", kNewton, 1e-5, "matched", "", {na, 0.05, na}, {na, 0.10, na}, kFreeVibration},
    // ---------------------------------------------------------------- Bullet 3.24 (double), btMultiBody
    {"bullet", "resonance", kHertz, 2e-5, "matched", "", {0.03, 0.05, 0.05}, {0.03, 0.15, 0.07}, kHertzStep},
    {"bullet",
     "resonance",
     kSpringDashpot,
     1e-5,
     "matched",
     "",
     {0.03, 0.05, 0.05},
     {0.03, 0.15, 0.10},
     kImplicitSpringDashpot},
    {"bullet", "resonance", kNewton, 5e-5, "matched", "", {0.03, 0.05, na}, {0.03, 0.15, na}, kBulletNewton},
    {"bullet", "pre_resonance", kHertz, 2e-5, "matched", "", {0.03, 0.05, 0.05}, {0.03, 0.10, 0.07}, kHertzStep},
    {"bullet",
     "pre_resonance",
     kSpringDashpot,
     1e-5,
     "matched",
     "",
     {0.03, 0.05, 0.05},
     {0.03, 0.10, 0.10},
     kImplicitSpringDashpot},
    {"bullet", "pre_resonance", kNewton, 5e-5, "matched", "", {0.03, 0.05, na}, {0.03, 0.10, na}, kBulletNewton},
    {"bullet", "post_resonance", kHertz, 5e-5, "matched", "", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"bullet", "free_vibration", kHertz, 1e-5, "matched", "", {na, 0.05, 0.05}, {na, 0.10, 0.07}, kFreeVibration},
    {"bullet",
     "free_vibration",
     kSpringDashpot,
     1e-5,
     "matched",
     "",
     {na, 0.25, 0.05},
     {na, 0.30, 0.10},
     kFreeVibrationSpringDashpot},
    {"bullet", "free_vibration", kNewton, 1e-5, "matched", "", {na, 0.05, na}, {na, 0.10, na}, kFreeVibration},
    // ---------------------------------------------------------------- DART 6.12.1, semi-implicit Euler, implicit joint
    // springs
    {"dart", "resonance", kHertz, 2e-5, "matched", "", {0.03, 0.05, 0.05}, {0.03, 0.15, 0.07}, kHertzStep},
    {"dart",
     "resonance",
     kSpringDashpot,
     5e-5,
     "matched",
     "",
     {0.03, 0.05, 0.05},
     {0.03, 0.15, 0.10},
     kDartSpringDashpot},
    {"dart", "resonance", kNewton, 2e-5, "matched", "length_unit=cm", {0.03, 0.05, na}, {0.03, 0.15, na}, kDartNewton},
    {"dart",
     "pre_resonance",
     kHertz,
     2e-5,
     "matched",
     "",
     {0.03, 0.10, 0.05},
     {0.03, 0.12, 0.07},
     kImplicitJointSpringsPreResonance},
    {"dart",
     "pre_resonance",
     kSpringDashpot,
     5e-5,
     "matched",
     "",
     {0.03, 0.10, 0.05},
     {0.03, 0.12, 0.10},
     kImplicitJointSpringsPreResonance},
    {"dart",
     "pre_resonance",
     kNewton,
     2e-5,
     "matched",
     "length_unit=cm",
     {0.03, 0.10, na},
     {0.03, 0.12, na},
     kImplicitJointSpringsPreResonance},
    {"dart", "post_resonance", kHertz, 1e-4, "matched", "", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"dart", "free_vibration", kHertz, 1e-5, "matched", "", {na, 0.05, 0.05}, {na, 0.10, 0.07}, kFreeVibration},
    {"dart",
     "free_vibration",
     kSpringDashpot,
     1e-5,
     "matched",
     "",
     {na, 0.25, 0.05},
     {na, 0.30, 0.10},
     kFreeVibrationSpringDashpot},
    {"dart",
     "free_vibration",
     kNewton,
     1e-5,
     "matched",
     "length_unit=cm",
     {na, 0.05, na},
     {na, 0.10, na},
     kFreeVibration},
    // ---------------------------------------------------------------- Simbody 3.7, semi-explicit Euler, explicit hinge
    // springs
    {"simbody", "resonance", kHertz, 2e-5, "matched", "", {0.03, 0.05, 0.05}, {0.03, 0.15, 0.07}, kSimbodyHertz},
    {"simbody",
     "resonance",
     kSpringDashpot,
     5e-5,
     "matched",
     "",
     {0.03, 0.05, 0.05},
     {0.03, 0.15, 0.10},
     kSimbodySpringDashpot},
    {"simbody", "resonance", kNewton, 2e-5, "matched", "", {0.03, 0.05, na}, {0.03, 0.15, na}, kSimbodyNewton},
    {"simbody", "pre_resonance", kHertz, 2e-5, "matched", "", {0.03, 0.05, 0.05}, {0.03, 0.10, 0.07}, kSimbodyHertz},
    {"simbody",
     "pre_resonance",
     kSpringDashpot,
     5e-5,
     "matched",
     "",
     {0.03, 0.05, 0.05},
     {0.03, 0.10, 0.10},
     kSimbodySpringDashpot},
    {"simbody", "pre_resonance", kNewton, 2e-5, "matched", "", {0.03, 0.05, na}, {0.03, 0.10, na}, kSimbodyNewton},
    {"simbody", "post_resonance", kHertz, 5e-5, "matched", "", {0, 0.02, na}, {0, 0.04, na}, kSimbodyPostResonance},
    {"simbody", "free_vibration", kHertz, 1e-5, "matched", "", {na, 0.05, 0.05}, {na, 0.10, 0.07}, kFreeVibration},
    {"simbody",
     "free_vibration",
     kSpringDashpot,
     1e-5,
     "matched",
     "",
     {na, 0.25, 0.05},
     {na, 0.30, 0.10},
     kFreeVibrationSpringDashpot},
    {"simbody", "free_vibration", kNewton, 1e-5, "matched", "", {na, 0.05, na}, {na, 0.10, na}, kFreeVibration},
    // ---------------------------------------------------------------- Siconos 4.4, Moreau-Jean time stepping, the
    // linearised chains as one linear Lagrangian system
    {"siconos", "resonance", kHertz, 5e-5, "matched", "", {0.03, 0.05, 0.07}, {0.03, 0.15, 0.09}, kSiconosHertz},
    {"siconos",
     "resonance",
     kSpringDashpot,
     5e-5,
     "matched",
     "",
     {0.03, 0.05, 0.10},
     {0.03, 0.15, 0.10},
     kSiconosSpringDashpot},
    {"siconos", "resonance", kNewton, 5e-5, "matched", "", {0.03, 0.05, na}, {0.03, 0.15, na}, kSiconosNewton},
    {"siconos", "pre_resonance", kHertz, 5e-5, "matched", "", {0.03, 0.05, 0.07}, {0.03, 0.10, 0.09}, kSiconosHertz},
    {"siconos",
     "pre_resonance",
     kSpringDashpot,
     5e-5,
     "matched",
     "",
     {0.03, 0.05, 0.10},
     {0.03, 0.10, 0.10},
     kSiconosSpringDashpot},
    {"siconos", "pre_resonance", kNewton, 5e-5, "matched", "", {0.03, 0.05, na}, {0.03, 0.10, na}, kSiconosNewton},
    {"siconos", "post_resonance", kHertz, 1e-4, "injected", "", {0, 0.02, na}, {0, 0.04, na}, kSiconosPostResonance},
    {"siconos", "free_vibration", kHertz, 2e-5, "matched", "", {na, 0.05, 0.05}, {na, 0.10, 0.07}, kFreeVibration},
    {"siconos",
     "free_vibration",
     kSpringDashpot,
     2e-5,
     "matched",
     "",
     {na, 0.25, 0.05},
     {na, 0.30, 0.10},
     kFreeVibrationSpringDashpot},
    {"siconos", "free_vibration", kNewton, 1e-5, "matched", "", {na, 0.05, na}, {na, 0.10, na}, kFreeVibration},
};

}  // namespace ib
