// A shared library that is not a plugin: no entry points.
extern "C" int not_a_plugin() { return 1; }
