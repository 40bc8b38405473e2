#pragma once
#include <stdexcept>
#include <string>

namespace svo {

/// The one exception type svo throws for bad input or an unusable environment.
/// Its message is a complete sentence a user can act on (it names the file
/// and the problem); the CLI prints it on one line and exits non-zero.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
};

} // namespace svo
