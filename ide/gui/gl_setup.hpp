// OpenGL set-up shared by every program that shows the 3D view (vsim-ide, the IDE benchmarks):
// call before the QApplication is made.
#pragma once

namespace ide {

// Every context OpenGL 3.3 core, no multisampling in the window (under a software renderer it
// doubles the frame time); Mesa's software renderer (llvmpipe) may use all cores but one, so that
// drawing never takes the kernel thread's core (LP_NUM_THREADS, unless the user set it).
void setUpOpenGl();

}  // namespace ide
