// Tests of the Newton loop itself on scalar equations with known Newton behaviour.
#include <catch2/catch.hpp>

#include <cmath>

#include "solvers/newton.hpp"

using namespace tirefe;

namespace {

/// One equation R(u) = atan(u - root): full Newton from |u0 - root| > 1.3917 moves away in
/// growing oscillations (the classic case where the tangent overshoots).
class ArctanEquation : public StepEquations {
 public:
  ArctanEquation(double start, double root) : u_(start), root_(root) {
    tangent_.resize(1, 1);
    tangent_.insert(0, 0) = 1.0;
    tangent_.makeCompressed();
  }
  void evaluate(bool with_tangent, Eigen::VectorXd& residual, double& force_level) override {
    residual.resize(1);
    residual[0] = std::atan(u_ - root_);
    // Without the tangent, one that no solve may use: a stale or skipped tangent fails loudly.
    tangent_.coeffRef(0, 0) = with_tangent ? 1.0 / (1.0 + (u_ - root_) * (u_ - root_)) : std::nan("");
    force_level = 1.0;
    ++(with_tangent ? tangents_ : residuals_alone_);
  }
  const SparseMatrix& tangent() const override { return tangent_; }
  double apply_increment(const Eigen::VectorXd& increment) override {
    u_ += increment[0];
    return std::abs(increment[0]) / (1.0 + std::abs(u_));
  }
  double u() const { return u_; }
  int tangents() const { return tangents_; }
  int residuals_alone() const { return residuals_alone_; }

 private:
  double u_, root_;
  SparseMatrix tangent_;
  int tangents_ = 0, residuals_alone_ = 0;
};

/// R(u) = u - root with a tangent 'stiffer' times too stiff: each increment takes 1/stiffer
/// of the error away, a linear convergence whose reduction does not grow. Without the
/// tangent, one that no solve may use (as above).
class StiffTangentEquation : public StepEquations {
 public:
  StiffTangentEquation(double start, double root, double stiffer) : u_(start), root_(root), stiffer_(stiffer) {
    tangent_.resize(1, 1);
    tangent_.insert(0, 0) = stiffer;
    tangent_.makeCompressed();
  }
  void evaluate(bool with_tangent, Eigen::VectorXd& residual, double& force_level) override {
    residual.resize(1);
    residual[0] = u_ - root_;
    tangent_.coeffRef(0, 0) = with_tangent ? stiffer_ : std::nan("");
    force_level = 1.0;
  }
  const SparseMatrix& tangent() const override { return tangent_; }
  double apply_increment(const Eigen::VectorXd& increment) override {
    u_ += increment[0];
    return std::abs(increment[0]) / (1.0 + std::abs(u_));
  }
  double u() const { return u_; }

 private:
  double u_, root_, stiffer_;
  SparseMatrix tangent_;
};

}  // namespace

TEST_CASE("Newton converges quadratically where it can, and backtracks out of overshooting cycles", "[newton]") {
  KluSolver solver;
  SECTION("close start: full steps, no backtracking") {
    ArctanEquation equation(0.5 + 3.0, 3.0);
    NewtonSolver newton;
    solver.analyze(equation.tangent());
    const NewtonReport& report = newton.solve(equation, solver);
    CHECK(report.backtracks == 0);
    CHECK(equation.u() == Approx(3.0).margin(1e-12));
    CHECK(report.iterations <= 5);
  }
  SECTION("far start: plain Newton diverges, backtracking converges") {
    NewtonSettings plain;
    plain.max_backtracks = 0;
    ArctanEquation diverging(2.0 + 3.0, 3.0);
    NewtonSolver plain_newton(plain);
    solver.analyze(diverging.tangent());
    CHECK_THROWS_AS(plain_newton.solve(diverging, solver), ConvergenceFailure);

    ArctanEquation equation(2.0 + 3.0, 3.0);
    NewtonSolver newton;
    const NewtonReport& report = newton.solve(equation, solver);
    CHECK(report.backtracks > 0);
    CHECK(equation.u() == Approx(3.0).margin(1e-9));
  }
}

TEST_CASE("Newton skips the tangent of the evaluation it expects to converge, on plain Newton's iterates", "[newton]") {
  KluSolver solver;
  NewtonSettings plain;
  plain.residual_only_when_converging = false;
  SECTION("quadratic convergence: the converged evaluation is of the residual alone") {
    // |R| 0.46, 0.079, 3.4e-4 (3.4e-4 * 3.4e-4 / 0.079 = 1.4e-6 < 3e-6 expected), 2.5e-11.
    ArctanEquation reference(0.5 + 3.0, 3.0), equation(0.5 + 3.0, 3.0);
    solver.analyze(reference.tangent());
    plain.residual_tolerance = 1e-6;
    const NewtonReport plain_report = NewtonSolver(plain).solve(reference, solver);
    NewtonSettings settings = plain;
    settings.residual_only_when_converging = true;
    NewtonSolver newton(settings);
    const NewtonReport& report = newton.solve(equation, solver);
    CHECK(report.iterations == plain_report.iterations);
    CHECK(report.residual_norms == plain_report.residual_norms);  // the same iterates, bit for bit
    CHECK(equation.u() == reference.u());
    CHECK(report.residual_only == 1);
    CHECK(report.retaken == 0);
    CHECK(equation.tangents() == reference.tangents() - 1);
    CHECK(reference.residuals_alone() == 0);
  }
  // The constant tangent makes the chord increment plain Newton's: the same iterations
  // and the same solution, with and without the residual-only evaluation.
  auto solve_halving = [&](double tolerance) {
    StiffTangentEquation reference(1.0, 0.0, 2.0), equation(1.0, 0.0, 2.0);
    solver.analyze(reference.tangent());
    plain.residual_tolerance = tolerance;
    const NewtonReport plain_report = NewtonSolver(plain).solve(reference, solver);
    NewtonSettings settings = plain;
    settings.residual_only_when_converging = true;
    const NewtonReport report = NewtonSolver(settings).solve(equation, solver);
    CHECK(report.iterations == plain_report.iterations);
    CHECK(equation.u() == reference.u());
    return report;
  };
  SECTION("a reduction that does not grow: one chord increment with the last factors") {
    // Halving from 1: 2^-9 < 3e-3 is expected to converge, 2^-10 < 1e-3 does.
    const NewtonReport report = solve_halving(1e-3);
    CHECK(report.iterations == 10);
    CHECK(report.residual_only == 2);  // at 2^-9 (a chord follows) and 2^-10 (converged)
    CHECK(report.chords == 1);
    CHECK(report.retaken == 0);
  }
  SECTION("a chord that does not converge either: the tangent is evaluated again at the same state") {
    const NewtonReport report = solve_halving(3e-3);  // 2^-7 expected to converge: a chord; 2^-8 retaken
    CHECK(report.iterations == 9);
    CHECK(report.residual_only == 3);  // at 2^-7 (a chord follows), 2^-8 (retaken), 2^-9
    CHECK(report.chords == 1);
    CHECK(report.retaken == 1);
  }
  SECTION("a caller that reads the converged tangent gets it") {
    struct TangentReader : ArctanEquation {
      using ArctanEquation::ArctanEquation;
      bool wants_converged_tangent() const override { return true; }
    } equation(0.5 + 3.0, 3.0);
    solver.analyze(equation.tangent());
    NewtonSettings settings;
    settings.residual_tolerance = 1e-6;
    NewtonSolver newton(settings);
    const NewtonReport& report = newton.solve(equation, solver);
    CHECK(report.residual_only == 0);
    CHECK(equation.residuals_alone() == 0);
    CHECK(std::isfinite(equation.tangent().coeff(0, 0)));
  }
}
