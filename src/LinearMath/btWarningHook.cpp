// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btWarningHook.h"

#include <cstdio>

#include "LinearMath/btIDebugDraw.h"

namespace
{
btWarningHookFunc gHook = 0;
void* gHookUserData = 0;
}  // namespace

void btSetWarningHook(btWarningHookFunc hook, void* userData)
{
	gHook = hook;
	gHookUserData = userData;
}

btWarningHookFunc btGetWarningHook() { return gHook; }

void btReportWarning(const char* message, btIDebugDraw* drawer)
{
	if (!message) return;
	if (gHook) gHook(message, gHookUserData);
	if (drawer) drawer->reportErrorWarning(message);
	if (!gHook && !drawer) std::fputs(message, stderr);
}
