// The JSS face (face.hpp): written by the face work.
#include "jaus/jss_face/face.hpp"
