// A scalar field f(t, x, y) given in a scene as a number or a muparser expression (boundary values,
// tractions, body forces). Not thread-safe: evaluate from one thread (systems evaluate expressions in
// serial loops over boundary nodes, or once per step into a column).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace loom {

class Expression {
 public:
  // Throws InputError naming `where` (file:line:column and key) if the text does not compile or uses a
  // variable other than t, x, y (and z when dimension = 3).
  Expression(const std::string& text, const std::string& where, int dimension = 2);
  ~Expression();
  Expression(Expression&&) noexcept;
  Expression& operator=(Expression&&) noexcept;
  Expression(const Expression&) = delete;
  Expression& operator=(const Expression&) = delete;

  double operator()(double t, double x, double y, double z = 0.0) const;
  const std::string& text() const;
  // The muparser message if `text` does not compile (or uses an unknown variable), empty if it does.
  static std::string compile_error(const std::string& text, int dimension = 2);
  // True when the value does not depend on t, x, y, z (a plain number).
  bool is_constant() const;
  bool depends_on_time() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Evaluates a formula in named constants once (e.g. alpha_s = "K/10" in the bulk and shear moduli).
// On failure returns NaN and sets *error to muparser's message.
double evaluate_formula(const std::string& text, const std::vector<std::pair<std::string, double>>& constants,
                        std::string* error);

}  // namespace loom
