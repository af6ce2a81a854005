#include "fitting/brent.hpp"

#include <algorithm>
#include <cmath>

#include "fitting/objective.hpp"

namespace tirefe::fitting {

namespace {

constexpr double kGolden = 1.618033988749895;          // bracket growth
constexpr double kGoldenSection = 0.3819660112501051;  // 2 - golden ratio

struct Point {
  double x, f;
};

// Thrown by Search::evaluate when the budget is spent; caught in minimize_scalar.
struct BudgetSpent {};

class Search {
 public:
  explicit Search(const ScalarSearch& search) : search_(search) {}

  Point evaluate(double x, const char* step) {
    if (evaluations_ >= search_.max_evaluations) throw BudgetSpent{};
    ++evaluations_;
    double f = search_.function(x);
    if (std::isnan(f)) f = std::numeric_limits<double>::infinity();
    if (!(f >= best_.f)) best_ = {x, f};  // also the first point (best_.f starts as NaN)
    if (search_.on_step) search_.on_step(step, best_.x, best_.f);
    return {x, f};
  }
  double clamp(double x) const { return std::min(std::max(x, search_.lower), search_.upper); }
  double tolerance(double x) const { return search_.tolerance(x); }
  double first_growth() const { return search_.first_growth; }
  void set_best(Point point) { best_ = point; }
  const Point& best() const { return best_; }
  int evaluations() const { return evaluations_; }

 private:
  const ScalarSearch& search_;
  Point best_{0.0, std::numeric_limits<double>::quiet_NaN()};
  int evaluations_ = 0;
};

struct Bracket {
  Point low, middle, high;  // f(middle) <= f(low), f(high); low/high in either order
  bool at_bound = false;    // the minimum is on the bound at 'middle'
};

// The minimum between 'inner' (f >= f(edge)) and 'edge' on a bound: on the bound if the
// objective still falls toward it just inside, else bracketed by a point just inside.
Bracket settle_at_bound(Search& search, Point inner, Point edge) {
  if (std::abs(inner.x - edge.x) <= 2.0 * search.tolerance(edge.x)) return {inner, edge, edge, true};
  const double inside = edge.x + (inner.x > edge.x ? 1.0 : -1.0) * search.tolerance(edge.x);
  const Point probe = search.evaluate(inside, "bracket");
  if (probe.f >= edge.f) return {inner, edge, edge, true};
  return {inner, probe, edge, false};
}

// A bracket much wider on one side of its middle (the first step landed close to the
// minimum) is narrowed by one point mirroring the near side: Brent's parabolas then start
// from three nearby points instead of one far away.
Bracket tightened(Search& search, const Bracket& bracket) {
  const Point& middle = bracket.middle;
  const bool low_far = std::abs(bracket.low.x - middle.x) > 4.0 * std::abs(bracket.high.x - middle.x);
  const bool high_far = std::abs(bracket.high.x - middle.x) > 4.0 * std::abs(bracket.low.x - middle.x);
  if (!low_far && !high_far) return bracket;
  const Point& near = low_far ? bracket.high : bracket.low;
  const Point& far = low_far ? bracket.low : bracket.high;
  const Point mirror = search.evaluate(2.0 * middle.x - near.x, "bracket");
  if (mirror.f >= middle.f) return {mirror, middle, near, false};
  return {far, mirror, middle, false};
}

Bracket bracket_minimum(Search& search, Point start, double step) {
  double x1 = search.clamp(start.x + step);
  if (x1 == start.x) x1 = search.clamp(start.x - step);  // starting on the bound ahead
  const Point first = search.evaluate(x1, "bracket");
  Point behind = start, best = first;
  if (first.f > start.f) {  // uphill: try the other side
    const double x2 = search.clamp(start.x - (x1 - start.x));
    if (x2 == start.x) return settle_at_bound(search, first, start);
    const Point other = search.evaluate(x2, "bracket");
    if (other.f >= start.f) return {other, start, first, false};
    best = other;
  }
  // Steps grow with the distance travelled from the start: a first step that fell short
  // (a probe just beyond it still went down) is followed by a long one, not a creep. The
  // first step was no estimate of the minimum if it went uphill.
  double growth = best.x == first.x ? search.first_growth() : kGolden;
  for (;;) {
    const double next_x = search.clamp(best.x + growth * (best.x - start.x));
    growth = kGolden;
    if (next_x == best.x) return settle_at_bound(search, behind, best);
    const Point next = search.evaluate(next_x, "bracket");
    if (next.f >= best.f) return tightened(search, {behind, best, next, false});
    behind = best;
    best = next;
  }
}

// Brent's method on a bracket; the bracket's end points seed w and v, so that the
// first step can already be parabolic.
void brent(Search& search, const Bracket& bracket) {
  double a = std::min(bracket.low.x, bracket.high.x), b = std::max(bracket.low.x, bracket.high.x);
  Point x = bracket.middle;
  Point w = bracket.low.f <= bracket.high.f ? bracket.low : bracket.high;
  Point v = bracket.low.f <= bracket.high.f ? bracket.high : bracket.low;
  double step = 0.0, step_before = b - a;
  for (;;) {
    const double middle = 0.5 * (a + b);
    const double tol1 = 0.5 * search.tolerance(x.x), tol2 = 2.0 * tol1;
    if (std::abs(x.x - middle) <= tol2 - 0.5 * (b - a)) return;  // [a, b] within x +- tolerance
    bool parabolic = false;
    if (std::abs(step_before) > tol1 && std::isfinite(w.f) && std::isfinite(v.f)) {
      const double r = (x.x - w.x) * (x.f - v.f);
      double q = (x.x - v.x) * (x.f - w.f);
      double p = (x.x - v.x) * q - (x.x - w.x) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::abs(q);
      // Accept the vertex if it is inside (a, b) and moves less than half the step before last.
      if (std::abs(p) < std::abs(0.5 * q * step_before) && p > q * (a - x.x) && p < q * (b - x.x)) {
        step_before = step;
        step = p / q;
        parabolic = true;
        const double u = x.x + step;
        if (u - a < tol2 || b - u < tol2) step = middle >= x.x ? tol1 : -tol1;
      }
    }
    if (!parabolic) {
      step_before = x.x >= middle ? a - x.x : b - x.x;
      step = kGoldenSection * step_before;
    }
    const double u_x = std::abs(step) >= tol1 ? x.x + step : x.x + (step >= 0.0 ? tol1 : -tol1);
    const Point u = search.evaluate(u_x, parabolic ? "parabolic" : "golden");
    if (u.f <= x.f) {
      (u.x >= x.x ? a : b) = x.x;
      v = w;
      w = x;
      x = u;
    } else {
      (u.x < x.x ? a : b) = u.x;
      if (u.f <= w.f || w.x == x.x) {
        v = w;
        w = u;
      } else if (u.f <= v.f || v.x == x.x || v.x == w.x) {
        v = u;
      }
    }
  }
}

}  // namespace

ScalarMinimum minimize_scalar(const ScalarSearch& search, double x0, double step, double f0) {
  if (!(step != 0.0) || !std::isfinite(step)) throw std::invalid_argument("the first step must be finite and non-zero");
  if (!(search.lower < search.upper) || x0 < search.lower || x0 > search.upper)
    throw std::invalid_argument("the start must lie inside [lower, upper]");
  Search state(search);
  ScalarMinimum minimum;
  try {
    const Point start = std::isnan(f0) ? state.evaluate(x0, "initial") : Point{x0, f0};
    if (!std::isnan(f0)) state.set_best(start);
    const Bracket bracket = bracket_minimum(state, start, step);
    if (bracket.at_bound) {
      minimum.outcome = ScalarMinimum::Outcome::AtBound;
    } else {
      brent(state, bracket);
      minimum.outcome = ScalarMinimum::Outcome::Converged;
    }
  } catch (const BudgetSpent&) {
    minimum.outcome = ScalarMinimum::Outcome::MaxEvaluations;
  }
  minimum.x = state.best().x;
  minimum.f = state.best().f;
  minimum.evaluations = state.evaluations();
  return minimum;
}

FitResult fit_brent(const FitProblem& problem, const FitOptions& options) {
  if (problem.parameters.size() != 1)
    throw std::invalid_argument("Brent's method fits one parameter; use levenberg_marquardt for " +
                                std::to_string(problem.parameters.size()));
  FitResult result;
  result.method = "brent";
  Objective objective(problem, options, result);
  const std::vector<bool> free{true};

  Eigen::VectorXd z = objective.initial();
  Objective::Evaluation at = objective.evaluate_initial(z);
  objective.record(z, at.objective, "initial");
  Eigen::MatrixXd jacobian = objective.jacobian(z, at);
  Assessment assessment = objective.assess(z, at, jacobian, free);
  if (!assessment.identifiable) {
    objective.finish(z, at, assessment, FitStatus::NotIdentifiable, "", false);
    return result;
  }

  // First step: Gauss-Newton in the parameter itself, dp = -J^T r / J^T J with J = dr/dp
  // (exact if the predictions are linear in p, as a force is nearly linear in a stiffness),
  // limited to a factor 10 (log) or to the parameter's scale, and at least 10 tolerances.
  const double value = objective.physical(z)[0];
  const double dz_dp = problem.parameters[0].log ? 1.0 / value : 1.0;
  const double change = -jacobian.col(0).dot(at.residuals) / (jacobian.col(0).squaredNorm() * dz_dp);
  double step = problem.parameters[0].log ? std::log(std::clamp(1.0 + change / value, 0.1, 10.0))
                                          : std::clamp(change, -objective.scale(0, z[0]), objective.scale(0, z[0]));
  const double smallest = 10.0 * options.tolerance * objective.scale(0, z[0]);
  if (std::abs(step) < smallest) step = std::copysign(smallest, step);

  // Keep the evaluation of the best point for the prediction and the statistics.
  Objective::Evaluation best = at;
  Eigen::VectorXd best_z = z;
  ScalarSearch search;
  search.lower = objective.lower(0);
  search.upper = objective.upper(0);
  search.max_evaluations = std::max(0, options.max_evaluations - objective.evaluations());
  search.first_growth = 0.1;  // the Gauss-Newton step lands close to the minimum
  search.tolerance = [&](double x) { return options.tolerance * objective.scale(0, x); };
  search.function = [&](double x) {
    const Eigen::VectorXd trial = Eigen::VectorXd::Constant(1, x);
    Objective::Evaluation evaluation = objective.evaluate(trial);
    if (evaluation.objective < best.objective) {
      best = evaluation;
      best_z = trial;
    }
    return evaluation.objective;
  };
  search.on_step = [&](const char* kind, double x, double f) {
    objective.record(Eigen::VectorXd::Constant(1, x), f, kind);
  };
  const ScalarMinimum minimum = minimize_scalar(search, z[0], step, at.objective);

  FitStatus status = FitStatus::Converged;
  std::string message;
  std::vector<bool> free_at_end = free;
  if (minimum.outcome == ScalarMinimum::Outcome::AtBound) {
    status = FitStatus::AtBound;
    free_at_end[0] = false;
    message = "the best fit is on the " + std::string(objective.on_lower(0, best_z[0]) ? "lower" : "upper") +
              " bound of '" + problem.parameters[0].name + "' (the objective still falls there)";
  } else if (minimum.outcome == ScalarMinimum::Outcome::MaxEvaluations) {
    status = FitStatus::MaxEvaluations;
    message = "no convergence within " + std::to_string(options.max_evaluations) + " evaluations";
  }
  jacobian = objective.jacobian(best_z, best);
  assessment = objective.assess(best_z, best, jacobian, free_at_end);
  objective.finish(best_z, best, assessment, status, message);
  return result;
}

}  // namespace tirefe::fitting
