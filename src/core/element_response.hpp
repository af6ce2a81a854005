// Named responses of an element block (OpenSees' setResponse / getResponse): values its
// elements give at their points at a committed state (a contact point's gap, forces and
// slip; a spring's axial force), which output asks for by name. A kernel that has them
// declares
//     static constexpr int kResponsePoints = 1;                  // points per element
//     static const std::vector<ResponseName>& response_names();  // each one's name and unit
//     double response(int index, int point, const LocalState<kDofs>& local,
//                     const History& committed) const;
// and its ElementBlockOf gives them through ElementResponses (responses_of(block)). Adding
// a response is a name in that list and its value in response(): the result file's rows
// of a contact block (/contact/<block>/<name>) and the deck's history channels
// (model:history{ block = ..., response = ... }) ask for it by name.
#pragma once

#include <string>
#include <type_traits>
#include <vector>

#include "core/mesh.hpp"
#include "core/state.hpp"

namespace tirefe {

template <int Dofs>
struct LocalState;  // core/element.hpp

struct ResponseName {
  std::string name;
  std::string unit;
};

class ElementResponses {
 public:
  virtual ~ElementResponses() = default;
  /// The responses, by index.
  virtual const std::vector<ResponseName>& response_names() const = 0;
  /// The block's points: every element's, element by element.
  virtual int response_points() const = 0;
  /// Response 'index' at every point, at 'state' with the committed histories ('values' resized).
  virtual void response_values(int index, const State& state, std::vector<double>& values) const = 0;
  /// The same at one point (0-based).
  virtual double response_value(int index, int point, const State& state) const = 0;

  /// The index of the response 'name', -1 if there is none.
  int response_index(const std::string& name) const {
    const std::vector<ResponseName>& names = response_names();
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i].name == name) return static_cast<int>(i);
    return -1;
  }
};

namespace detail {
template <class Kernel, class = void>
struct HasResponses : std::false_type {};
template <class Kernel>
struct HasResponses<Kernel, std::void_t<decltype(Kernel::kResponsePoints)>> : std::true_type {};
}  // namespace detail

/// A base of ElementBlockOf<Kernel> (the Block): nothing for a kernel without responses,
/// ElementResponses read from its kernels and committed histories for one with them.
template <class Block, class Kernel, bool = detail::HasResponses<Kernel>::value>
class BlockResponses {};

template <class Block, class Kernel>
class BlockResponses<Block, Kernel, true> : public ElementResponses {
 public:
  const std::vector<ResponseName>& response_names() const override { return Kernel::response_names(); }
  int response_points() const override { return block().size() * Kernel::kResponsePoints; }
  void response_values(int index, const State& state, std::vector<double>& values) const override {
    values.resize(static_cast<size_t>(response_points()));
    for (int point = 0; point < response_points(); ++point) values[point] = response_value(index, point, state);
  }
  double response_value(int index, int point, const State& state) const override {
    const Block& elements = block();
    const int e = point / Kernel::kResponsePoints;
    LocalState<Block::kDofs> local;
    local.acceleration.setZero();  // stays zero for kernels that never read it
    elements.gather(e, state, local);
    return elements.kernel(e).response(index, point % Kernel::kResponsePoints, local, elements.committed_history(e));
  }

 private:
  const Block& block() const { return static_cast<const Block&>(*this); }
};

/// The named responses of an element block, or null when its kernel has none.
template <class Block>
const ElementResponses* responses_of(const Block& block) {
  return dynamic_cast<const ElementResponses*>(&block);
}

}  // namespace tirefe
