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
  void evaluate(bool, Eigen::VectorXd& residual, double& force_level) override {
    residual.resize(1);
    residual[0] = std::atan(u_ - root_);
    tangent_.coeffRef(0, 0) = 1.0 / (1.0 + (u_ - root_) * (u_ - root_));
    force_level = 1.0;
  }
  const SparseMatrix& tangent() const override { return tangent_; }
  double apply_increment(const Eigen::VectorXd& increment) override {
    u_ += increment[0];
    return std::abs(increment[0]) / (1.0 + std::abs(u_));
  }
  double u() const { return u_; }

 private:
  double u_, root_;
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
