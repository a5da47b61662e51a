// Plugins are compiled with hidden visibility; the classes they share with the host keep default
// visibility so that their type information (exceptions, dynamic types) is one across libraries.
#pragma once

#define TOPOMILL_API __attribute__((visibility("default")))
