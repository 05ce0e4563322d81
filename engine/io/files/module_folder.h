// SPDX-License-Identifier: MIT
// The folder libsilk itself was loaded from: where it finds what ships beside it (the bundled model,
// onnxruntime in the pip wheel), whatever the process's working folder or executable is.
#pragma once
#include <string>

namespace silk {

// UTF-8 folder of the module (libsilk.so / libsilk.dll, or the executable libsilk.a was linked
// into) holding this code, without symbolic links; "" when the platform cannot say.
std::string ModuleFolder();

}  // namespace silk
