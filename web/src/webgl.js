// Whether the browser draws WebGL in software (SwiftShader, llvmpipe: no
// GPU, or a headless browser).  There multisampling costs a rasterization
// per sample on the CPU that the editor's server and simulator share (a
// pendulum's frame about twice as long, the main thread and the server's
// answers waiting on it), so viewers draw without it.  Asked once, of a
// throwaway context.
let software = null;

export function softwareWebGL() {
  if (software !== null) return software;
  software = false;
  try {
    const gl = document.createElement('canvas').getContext('webgl');
    if (gl) {
      const info = gl.getExtension('WEBGL_debug_renderer_info');
      const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
      software = /swiftshader|llvmpipe|softpipe|software|basic render/i.test(name);
      const lose = gl.getExtension('WEBGL_lose_context');
      if (lose) lose.loseContext();
    }
  } catch { /* no WebGL: the viewer's own context says so */ }
  return software;
}
