// Exception types of the Fairlines engine. The Python bindings translate each one
// (see native/bindings/module.cpp); nothing in the engine aborts on user input.
#pragma once

#include <stdexcept>
#include <string>

namespace fairlines {

/// Base of every exception the engine throws on purpose; never thrown itself (each failure is
/// one of the kinds below, so a caller knows whether to change a value or retry).
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Thrown when an argument is malformed: wrong shape, NaN/inf, decreasing knots,
/// non-positive weights, unknown option name. Python: ValueError.
struct InvalidInput : Error {
  using Error::Error;
};

/// Thrown when a set of form parameters cannot be met by any curve of the requested
/// kind; the message names the parameters in conflict. Python: fl.InfeasibleFormParameters.
struct InfeasibleFormParameters : InvalidInput {
  using InvalidInput::InvalidInput;
};

/// Thrown when no blending surface fits clear of a hull/bulb seam on the hull (the boundary
/// would leave the hull); a caller may fall back to the plain union. Python: fl.NoBlendFits.
struct NoBlendFits : InvalidInput {
  using InvalidInput::InvalidInput;
};

/// Thrown when an iterative method fails to reach its tolerance on valid input.
/// Python: RuntimeError (fl.ConvergenceError).
struct ConvergenceError : Error {
  using Error::Error;
};

}  // namespace fairlines
