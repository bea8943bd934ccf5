#pragma once
// Exact event-driven simulation of the nonsmooth system (eqs. 1.1-1.2) from any initial state: free flight
// M x'' + K x = 0, impacts with Newton's law, lasting contact under Signorini's conditions. Each phase is a
// closed-form modal flow (eq. 3.12); events are the first crossings of the closed-form gap (flight) or
// contact force (contact), found with certified bounds, so that no grazing or short excursion is stepped over.
// Independent of the solver: its own eigenproblems, in physical coordinates.

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "spp/core/system.hpp"

namespace spp {

struct SimulateOptions {
  /// Simulated time T > 0; the last sample is at t = T exactly. At most 1e8 periods of the system's fastest mode
  /// (run() refuses more, naming the largest: the event search steps through each period; ~2.4 us each on a 5-dof
  /// chain).
  double duration = 0.0;
  double restitution = 0.0;  ///< Newton's coefficient e in [0, 1]: normal velocity after = -e * before
  /// Samples at these times (sorted, in [0, duration]) besides t = 0, the state after each event and t = T.
  std::vector<double> sample_times;
  bool sample_events = true;  ///< add a sample with the state just after each event
  long max_events = 10000000;
  /// Event tolerances, relative to the amplitude of the gap (flight) or force (contact) of the phase: an
  /// excursion below zero shallower than this is not an event; a start penetrating the obstacle by less than 100 times
  /// it (or 1e-9) relative to |g0| + |x0| is a start on it.
  double event_rel_tol = 1e-13;
  /// An impact slower than this (relative to the bound sum |a_k| omega_k on the gap's velocity), or whose
  /// rebound would rise less than a few event tolerances, is plastic: it is where an accumulation of impacts
  /// (chattering, e < 1) ends in lasting contact.
  double rest_velocity_rel_tol = 1e-8;
  /// Called every 256 events or samples from the thread that called run() (so a Python callback may take the GIL):
  /// returning false stops the run there with status Interrupted (Ctrl-C in Python). Empty: never called.
  std::function<bool()> progress;
  /// Throws std::invalid_argument naming the field, its value and the rule.
  void validate() const;
};

/// Uniform sample times k / per_unit in [0, duration].
std::vector<double> uniform_times(double duration, double per_unit);

enum class EventKind {
  Impact,        ///< gap reached 0 with a negative normal velocity; velocity reset by Newton's law
  ContactOnset,  ///< gap and normal velocity zero, constraint force non-negative: lasting contact begins
  Release        ///< the contact force would turn negative: free flight begins
};
const char* to_string(EventKind kind);
/// Its values: 0 .. 2 (Release last), each bound by python/bind (bind_outcome). Update with the enum.
constexpr int value_count(EventKind) {
  return 3;
}

struct Event {
  double t = 0.0;
  EventKind kind = EventKind::Impact;
  Eigen::VectorXd x, v_before, v_after;
  double normal_velocity_before = 0.0, normal_velocity_after = 0.0;
  double force = 0.0;  ///< contact force at the event (0 for an impact)
};

struct Sample {
  double t = 0.0;
  Eigen::VectorXd x, v;
  double gap = 0.0, force = 0.0;
  bool in_contact = false;
};

enum class SimulationStatus {
  NotRun,
  Success,     ///< reached t = duration
  EventLimit,  ///< stopped at max_events before t = duration (samples end at the last event)
  Stalled,     ///< over 100 events in a row without time passing (samples end there): a defect to report
  Interrupted  ///< SimulateOptions::progress returned false (samples end there)
};
const char* to_string(SimulationStatus status);
/// Its values: 0 .. 4 (Interrupted last), each bound by python/bind (bind_outcome). Update with the enum.
constexpr int value_count(SimulationStatus) {
  return 5;
}

struct SimulationResult {
  SimulationStatus status = SimulationStatus::NotRun;
  std::vector<Sample> samples;  ///< sorted by t; the last one at the end time
  std::vector<Event> events;
  long impacts = 0, contact_onsets = 0, releases = 0;
  double energy_initial = 0.0, energy_final = 0.0;
  double impact_energy_loss = 0.0;  ///< sum of (1 - e^2)/2 * v_n^2 / (w^T M^-1 w) over the impacts
  double end_time = 0.0;
  bool in_contact_at_end = false;
  std::string brief_report() const;
};

/// The two phase flows of a system, computed once (model/workspace split): reuse it for many simulations.
class Simulator {
 public:
  /// Cost O(n^3): the eigenproblems of both phases.
  explicit Simulator(const System& system);

  /// Simulates from (x0, v0) at t = 0 (both (n), in the system's units). Cost O(n^2) per event and per sample.
  /// Throws std::invalid_argument if the sizes are wrong, a value is not finite or the initial state penetrates the
  /// obstacle.
  SimulationResult run(const Eigen::VectorXd& x0, const Eigen::VectorXd& v0, const SimulateOptions& options) const;

  /// The state reached from (x0, v0) by the contact flow M x'' + K~ x = 0 (w^T x'' = 0: the normal position
  /// w^T x + g0 and velocity w^T v0 at the start are carried along, affine in time, i.e. the obstacle moves with the
  /// normal velocity w^T v0, as a point-symmetric SPP's does; zero for an axial SPP) for `contact_time`, then the free
  /// flight for `flight_time`, every event ignored: the potential orbit of an SPP (paper §3), which an inadmissible
  /// SPP follows although the simulator cannot. Both durations >= 0. Cost O(n^2).
  std::pair<Eigen::VectorXd, Eigen::VectorXd> follow_contact_then_flight(const Eigen::VectorXd& x0,
                                                                        const Eigen::VectorXd& v0,
                                                                        double contact_time,
                                                                        double flight_time) const;

  /// The longest duration run() accepts: 1e8 periods of the fastest mode of either phase (the event search steps
  /// through each; ~2.4 us each on a 5-dof chain); infinity for a system without a positive frequency.
  double max_duration() const;

  const System& system() const { return system_; }
  double energy(const Eigen::VectorXd& x, const Eigen::VectorXd& v) const;

  struct Phase {
    Eigen::VectorXd omega;  ///< modal frequencies
    Eigen::MatrixXd Phi;    ///< mass-normalised mode shapes (n x m): Phi^T M Phi = I
    Eigen::VectorXd x_s;    ///< equilibrium of the phase
    /// The quantity that must stay >= 0 in this phase (flight: the gap; contact: the force), affine in x:
    /// watched = offset + weights^T q in the phase's modal coordinates q.
    double offset = 0.0;
    Eigen::VectorXd weights;
  };

 private:
  System system_;
  Eigen::LLT<Eigen::MatrixXd> M_llt_;
  Eigen::VectorXd Minv_w_;  ///< M^-1 w
  Eigen::VectorXd normal_motion_;  ///< K^-1 w / (w^T K^-1 w): x_s + s normal_motion_ is a contact motion with w^T x = s
  double w_Minv_w_ = 0.0;
  Eigen::RowVectorXd force_row_;  ///< w^T M^-1 K / (w^T M^-1 w): contact force = force_row_ * x
  Phase flight_, contact_;
};

/// One-shot form of Simulator(system).run(x0, v0, options).
SimulationResult simulate(const System& system, const Eigen::VectorXd& x0, const Eigen::VectorXd& v0,
                          const SimulateOptions& options);

}  // namespace spp
