// Linked only into sanitizer builds of programs that load Vulkan: lavapipe and
// the validation layer leak at exit from libraries already unloaded by then, so
// LeakSanitizer can neither name nor suppress them. Address and UB checks stay on;
// every program that does not load Vulkan keeps leak checking.
extern "C" const char* __asan_default_options() { return "detect_leaks=0"; }
