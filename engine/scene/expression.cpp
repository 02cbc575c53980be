#include "engine/scene/expression.hpp"

#include <muParser.h>

#include <cmath>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/core/types.hpp"

namespace loom {

struct Expression::Impl {
  mu::Parser parser;
  double t = 0, x = 0, y = 0, z = 0;
  std::string text, where;
  bool constant = false, uses_time = false;
};

Expression::Expression(const std::string& text, const std::string& where, int dimension) : impl_(std::make_unique<Impl>()) {
  impl_->text = text;
  impl_->where = where;
  try {
    impl_->parser.DefineVar("t", &impl_->t);
    impl_->parser.DefineVar("x", &impl_->x);
    impl_->parser.DefineVar("y", &impl_->y);
    impl_->parser.DefineVar("z", &impl_->z);
    impl_->parser.DefineConst("pi", M_PI);
    impl_->parser.SetExpr(text);
    impl_->parser.Eval();  // compiles and reports undefined names
    const auto used = impl_->parser.GetUsedVar();
    impl_->constant = used.empty();
    impl_->uses_time = used.count("t") > 0;
    // A constant that is not a number (sqrt(-9.81), 1/0) is a mistake in the scene, found at `loom check`, not at
    // the first step that evaluates it.
    if (impl_->constant) {
      const double v = impl_->parser.Eval();
      if (!std::isfinite(v)) {
        std::ostringstream os;
        os << where << ": invalid expression \"" << text << "\": its value is not finite (" << v << ")";
        throw InputError(os.str());
      }
    }
    // z is defined so that a 2D scene's z gets a message that says why, not "unexpected token".
    if (dimension < 3 && used.count("z")) {
      std::ostringstream os;
      os << where << ": invalid expression \"" << text << "\": uses z, but the scene is two-dimensional (scene.dimension = "
         << dimension << "): the variables are t, x, y";
      throw InputError(os.str());
    }
  } catch (const mu::Parser::exception_type& e) {
    std::ostringstream os;
    os << where << ": invalid expression \"" << text << "\": " << e.GetMsg();
    throw InputError(os.str());
  }
}

Expression::~Expression() = default;
Expression::Expression(Expression&&) noexcept = default;
Expression& Expression::operator=(Expression&&) noexcept = default;

double Expression::operator()(double t, double x, double y, double z) const {
  impl_->t = t, impl_->x = x, impl_->y = y, impl_->z = z;
  const double v = impl_->parser.Eval();
  LOOM_CHECK(std::isfinite(v), RunError,
             impl_->where << ": expression \"" << impl_->text << "\" is not finite at t = " << t << ", x = " << x
                          << ", y = " << y);
  return v;
}

std::string Expression::compile_error(const std::string& text, int dimension) {
  try {
    Expression e(text, "", dimension);
  } catch (const InputError& err) {
    const std::string msg = err.what();
    const auto colon = msg.find("\": ");
    return colon == std::string::npos ? msg : msg.substr(colon + 3);
  }
  return {};
}

double evaluate_formula(const std::string& text, const std::vector<std::pair<std::string, double>>& constants,
                        std::string* error) {
  try {
    mu::Parser parser;
    for (const auto& [name, value] : constants) parser.DefineConst(name, value);
    parser.DefineConst("pi", M_PI);
    parser.SetExpr(text);
    const double v = parser.Eval();
    if (!std::isfinite(v)) {
      if (error) *error = "the value is not finite";
      return kNaN;
    }
    return v;
  } catch (const mu::Parser::exception_type& e) {
    if (error) *error = e.GetMsg();
    return kNaN;
  }
}

const std::string& Expression::text() const { return impl_->text; }
bool Expression::is_constant() const { return impl_->constant; }
bool Expression::depends_on_time() const { return impl_->uses_time; }

}  // namespace loom
