#include "host/plugin_registry.hpp"
int main() { return 0; }
