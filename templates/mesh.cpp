#include "templates/mesh.h"
