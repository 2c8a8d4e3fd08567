#pragma once
// Everything an SpFunc author needs, in one include: actors and components, USpFuncComponent,
// SpFuncDataBundle, SpArray, SpUtils and SP_LOG.

#include "core/base/log.h"
#include "core/spfunc/sp_func_component.h"
#include "core/spfunc/sp_utils.h"
#include "core/world/actor.h"
