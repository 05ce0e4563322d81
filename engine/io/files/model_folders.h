// SPDX-License-Identifier: MIT
// Where model folders live: the bundled model shipped beside libsilk and the user's models folder
// that `silk-export import-official --name` fills. The one rule every client (silkgen, the C API,
// silk_mesh, silk_export, the Blender add-on) asks through silk.h, so a model is found by name.
#pragma once
#include <string>
#include <vector>

#include "core/status.h"

namespace silk {

// $SILK_MODELS; else %LOCALAPPDATA%\silk\models (Windows), $XDG_DATA_HOME/silk/models (an
// absolute XDG_DATA_HOME) or $HOME/.local/share/silk/models. The folder need not exist yet.
// An error when none of these variables is set.
StatusOr<std::string> UserModelsDir();

// A model name: 1-100 characters of A-Z a-z 0-9 . _ -, not starting with '.' or '-' (so never a
// path: no separator, no "..", no drive letter). Ok, or an InvalidArgument stating the rule.
Status CheckModelName(const std::string& name);

// <UserModelsDir()>/<name> after CheckModelName.
StatusOr<std::string> UserModelDir(const std::string& name);

// The folders tried for the bundled model, in order: <libsilk's folder>/../model (the pip wheel,
// the Blender add-on), <libsilk's folder>/<lib-to-data>/silk/models/default (cmake --install),
// <libsilk's folder>/models/default (the Windows zip), then the source tree's models/default
// (a build tree's libsilk only).
std::vector<std::string> BundledModelCandidates();
// The first candidate holding a model.json, else an IoError listing where it looked.
StatusOr<std::string> BundledModelDir();

// What a caller's model argument means: "" = the bundled model; an existing folder = that folder
// (a path always wins); a model name (CheckModelName) = that folder of the user's models folder,
// or an IoError naming both places when neither exists; anything else is returned unchanged (the
// loader names the missing folder).
StatusOr<std::string> ResolveModelDir(const std::string& name_or_dir);

}  // namespace silk
