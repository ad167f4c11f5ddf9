// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_WARNING_HOOK_H
#define BT_WARNING_HOOK_H

/// Caliber extension: where warnings about bad input go in release builds (docs/bad-input.md).

class btIDebugDraw;

/// Receives each warning the library reports; userData is what was given to btSetWarningHook.
typedef void (*btWarningHookFunc)(const char* message, void* userData);

/// Installs hook (0 restores the default: standard error when no debug drawer is set).
void btSetWarningHook(btWarningHookFunc hook, void* userData = 0);
/// The installed hook, or 0.
btWarningHookFunc btGetWarningHook();

/// Reports message to the hook when one is installed and to drawer->reportErrorWarning when drawer is
/// set; to standard error when neither is.
void btReportWarning(const char* message, btIDebugDraw* drawer = 0);

#endif  // BT_WARNING_HOOK_H
