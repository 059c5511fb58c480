// A shared library that is not a plugin: no jaus_component_plugin symbol.
extern "C" __attribute__((visibility("default"))) int not_a_jaus_plugin() { return 1; }
