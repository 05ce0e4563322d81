// SPDX-License-Identifier: MIT
// silkgen's and silktok's command lines as UTF-8 on every platform: Windows hands main() its
// arguments in the ANSI code page (a "形状" folder arrives as "??"), so there main() reads them
// again from GetCommandLineW. Chosen over an activeCodePage=UTF-8 manifest, which needs
// Windows 10 1903 or later, changes the code page of the whole process, and does nothing for
// libsilk.dll loaded by another program (Blender): libsilk takes UTF-8 and converts itself.
#pragma once

namespace silkapp {

// Windows: replaces argc/argv with the UTF-8 arguments (storage lives until exit) and sets the
// console's output code page to UTF-8 so messages naming such paths print right. Elsewhere a no-op.
void UseUtf8Arguments(int& argc, char**& argv);

}  // namespace silkapp
