// The page side of glslcheck's WebGL backend: one WebGL2 context that compiles Shadertoy
// programs and renders them as Shadertoy's page does, into an RGBA32F framebuffer read back
// unquantised. Evaluated once in an about:blank page; Python calls window.glslcheck.* through
// page.evaluate (glslcheck/backends/webgl/browser.py). Written for glslcheck, no third-party code.
(() => {
  "use strict";
  const canvas = document.createElement("canvas");
  canvas.width = 1;
  canvas.height = 1;
  // Shadertoy's context attributes; rendering goes to our own float framebuffer anyway.
  const gl = canvas.getContext("webgl2", {
    alpha: false, depth: false, stencil: false, premultipliedAlpha: false,
    antialias: false, preserveDrawingBuffer: true, powerPreference: "high-performance",
  });
  const state = { programs: new Map(), nextId: 1, target: null, vertex: null, error: null };
  window.glslcheck = state;
  if (!gl) {
    state.error = "this browser gives no WebGL 2 context";
    return;
  }
  if (!gl.getExtension("EXT_color_buffer_float")) {
    state.error = "WebGL 2 has no EXT_color_buffer_float (no float render target)";
    return;
  }
  // Linear and mipmap filtering of the RGBA32F channel textures (Shadertoy enables it too; a
  // float texture without it is incomplete under a linear filter and reads (0, 0, 0, 1)).
  state.floatLinear = gl.getExtension("OES_texture_float_linear") !== null;

  // Shadertoy's vertex stage: one triangle over the viewport from a vertex buffer at location 0.
  const triangle = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, triangle);
  gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([-1, -1, 3, -1, -1, 3]), gl.STATIC_DRAW);
  const vao = gl.createVertexArray();
  gl.bindVertexArray(vao);
  gl.enableVertexAttribArray(0);
  gl.vertexAttribPointer(0, 2, gl.FLOAT, false, 0, 0);

  function compileShader(type, text) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, text);
    gl.compileShader(shader);
    const ok = gl.getShaderParameter(shader, gl.COMPILE_STATUS);
    return { shader, ok, log: gl.getShaderInfoLog(shader) || "" };
  }

  state.info = () => {
    const debug = gl.getExtension("WEBGL_debug_renderer_info");
    return {
      renderer: debug ? gl.getParameter(debug.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER),
      version: gl.getParameter(gl.VERSION),
      shading: gl.getParameter(gl.SHADING_LANGUAGE_VERSION),
      userAgent: navigator.userAgent,
    };
  };

  // Compile and link; {id} on success, {compileLog | linkLog} on failure (nothing is kept).
  state.compile = (vertexText, fragmentText) => {
    const vs = compileShader(gl.VERTEX_SHADER, vertexText);
    if (!vs.ok) { gl.deleteShader(vs.shader); return { vertexLog: vs.log }; }
    const fs = compileShader(gl.FRAGMENT_SHADER, fragmentText);
    if (!fs.ok) {
      gl.deleteShader(vs.shader); gl.deleteShader(fs.shader);
      return { compileLog: fs.log };
    }
    const program = gl.createProgram();
    gl.attachShader(program, vs.shader);
    gl.attachShader(program, fs.shader);
    gl.bindAttribLocation(program, 0, "pos");
    gl.linkProgram(program);
    gl.deleteShader(vs.shader);
    gl.deleteShader(fs.shader);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
      const log = gl.getProgramInfoLog(program) || "";
      gl.deleteProgram(program);
      return { linkLog: log || "the program does not link" };
    }
    const id = state.nextId++;
    const active = [];
    const count = gl.getProgramParameter(program, gl.ACTIVE_UNIFORMS);
    for (let i = 0; i < count; i++) active.push(gl.getActiveUniform(program, i).name);
    state.programs.set(id, { program, locations: new Map() });
    return { id, warnings: fs.log, active };
  };

  state.release = (ids) => {
    for (const id of ids) {
      const entry = state.programs.get(id);
      if (entry) { gl.deleteProgram(entry.program); state.programs.delete(id); }
    }
  };

  function location(entry, name) {
    if (!entry.locations.has(name)) entry.locations.set(name, gl.getUniformLocation(entry.program, name));
    return entry.locations.get(name);
  }

  function target(width, height) {
    const t = state.target;
    if (t && t.width === width && t.height === height) return t;
    if (t) { gl.deleteFramebuffer(t.fbo); gl.deleteTexture(t.texture); }
    const texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, width, height);
    gl.bindTexture(gl.TEXTURE_2D, null);
    const fbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
    const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
    if (status !== gl.FRAMEBUFFER_COMPLETE) throw new Error(`the RGBA32F framebuffer is incomplete (0x${status.toString(16)})`);
    state.target = { width, height, texture, fbo, pixels: new Float32Array(width * height * 4) };
    return state.target;
  }

  // uniforms: [[name, kind, values], ...] with kind one of 1f 3f 4f 1i 1fv 3fv.
  function setUniform(entry, name, kind, values) {
    const loc = location(entry, name);
    if (loc === null) return; // inactive: the compiler dropped it
    switch (kind) {
      case "1f": gl.uniform1f(loc, values[0]); break;
      case "2f": gl.uniform2f(loc, values[0], values[1]); break;
      case "3f": gl.uniform3f(loc, values[0], values[1], values[2]); break;
      case "4f": gl.uniform4f(loc, values[0], values[1], values[2], values[3]); break;
      case "1i": gl.uniform1i(loc, values[0]); break;
      case "1fv": gl.uniform1fv(loc, values); break;
      case "3fv": gl.uniform3fv(loc, values); break;
      default: throw new Error(`unknown uniform kind ${kind}`);
    }
  }

  function fromBase64(text) {
    if (Uint8Array.fromBase64) return Uint8Array.fromBase64(text);
    const raw = atob(text);
    const bytes = new Uint8Array(raw.length);
    for (let i = 0; i < raw.length; i++) bytes[i] = raw.charCodeAt(i);
    return bytes;
  }

  // Channel textures are uploaded once and kept by key until dropped: `textureBegin` gives the
  // size, filter, wrap and the byte length of each level (RGBA32F, level 0 first, row 0 at t
  // near 0: glslcheck's own mipmap pyramid, as on the GL backend, so every backend samples the
  // same texels), `textureChunk` fills the bytes in pieces small enough for the DevTools
  // protocol, `textureEnd` makes the texture. A cube map (`cube`) has six faces per level, +X,
  // -X, +Y, -Y, +Z, -Z one after the other; WebGL 2 filters it seamlessly, clamped to the edges.
  state.textures = new Map();
  state.textureBegin = (key, width, height, filter, wrap, sizes, cube) => {
    if (filter !== "nearest" && !state.floatLinear) {
      throw new Error("WebGL 2 has no OES_texture_float_linear: linear filtering of float channels is not available");
    }
    state.textures.set(key, { width, height, filter, wrap, cube, levels: sizes.map((n) => new Uint8Array(n)), texture: null });
    return true;
  };
  state.textureChunk = (key, level, offset, text) => {
    state.textures.get(key).levels[level].set(fromBase64(text), offset);
    return true;
  };
  state.textureEnd = (key) => {
    const c = state.textures.get(key);
    const texture = gl.createTexture();
    const target = c.cube ? gl.TEXTURE_CUBE_MAP : gl.TEXTURE_2D;
    gl.bindTexture(target, texture);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
    gl.texStorage2D(target, c.levels.length, gl.RGBA32F, c.width, c.height);
    c.levels.forEach((bytes, level) => {
      const w = Math.max(1, c.width >> level), h = Math.max(1, c.height >> level);
      const faces = c.cube ? 6 : 1, n = bytes.byteLength / 4 / faces;
      for (let f = 0; f < faces; f++) {
        const floats = new Float32Array(bytes.buffer, bytes.byteOffset + 4 * n * f, n);
        const place = c.cube ? gl.TEXTURE_CUBE_MAP_POSITIVE_X + f : gl.TEXTURE_2D;
        gl.texSubImage2D(place, level, 0, 0, w, h, gl.RGBA, gl.FLOAT, floats);
      }
    });
    const mag = c.filter === "nearest" ? gl.NEAREST : gl.LINEAR;
    const min = c.filter === "mipmap" ? gl.LINEAR_MIPMAP_LINEAR : mag;
    gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, min);
    gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, mag);
    const wrap = c.wrap === "repeat" ? gl.REPEAT : gl.CLAMP_TO_EDGE;
    gl.texParameteri(target, gl.TEXTURE_WRAP_S, wrap);
    gl.texParameteri(target, gl.TEXTURE_WRAP_T, wrap);
    gl.bindTexture(target, null);
    c.levels = null;
    c.texture = texture;
    return true;
  };
  state.textureDrop = (keys) => {
    for (const key of keys) {
      const c = state.textures.get(key);
      if (c && c.texture) gl.deleteTexture(c.texture);
      state.textures.delete(key);
    }
    return true;
  };

  // The units are 0..3 as iChannel0..3, each a key of an uploaded texture or null (unbound).
  function bindChannels(channels) {
    channels.forEach((key, unit) => {
      const c = key === null ? null : state.textures.get(key);
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_2D, c !== null && !c.cube ? c.texture : null);
      gl.bindTexture(gl.TEXTURE_CUBE_MAP, c !== null && c.cube ? c.texture : null);
    });
    gl.activeTexture(gl.TEXTURE0);
  }

  function unbindChannels() {
    for (let unit = 0; unit < 4; unit++) {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_2D, null);
      gl.bindTexture(gl.TEXTURE_CUBE_MAP, null);
    }
    gl.activeTexture(gl.TEXTURE0);
  }

  // Little-endian float32 bytes as base64 (the cheapest way through the DevTools protocol).
  function base64(floats) {
    const bytes = new Uint8Array(floats.buffer, floats.byteOffset, floats.byteLength);
    let text = "";
    for (let i = 0; i < bytes.length; i += 0x8000) {
      text += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    }
    return btoa(text);
  }

  // One frame: every sub-pixel offset drawn and read back, summed in float64 (JS numbers) in
  // the order given, divided once and rounded to float32 once (as the GL backend does).
  state.render = (id, width, height, uniforms, offsets, channels) => {
    const entry = state.programs.get(id);
    if (!entry) throw new Error(`no program ${id}`);
    const t = target(width, height); // first: making a target binds (then unbinds) a texture
    if (channels) bindChannels(channels);
    try {
      return draw(entry, t, width, height, uniforms, offsets);
    } finally {
      unbindChannels();
    }
  };

  function draw(entry, t, width, height, uniforms, offsets) {
    gl.bindFramebuffer(gl.FRAMEBUFFER, t.fbo);
    gl.viewport(0, 0, width, height);
    gl.disable(gl.BLEND);
    gl.useProgram(entry.program);
    gl.bindVertexArray(vao);
    for (const [name, kind, values] of uniforms) setUniform(entry, name, kind, values);
    let sum = null;
    for (const offset of offsets) {
      if (offset !== null) setUniform(entry, "glslcheck_offset", "2f", offset);
      gl.clearColor(0, 0, 0, 0);
      gl.clear(gl.COLOR_BUFFER_BIT);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      gl.readPixels(0, 0, width, height, gl.RGBA, gl.FLOAT, t.pixels);
      if (offsets.length === 1) break;
      if (sum === null) sum = new Float64Array(t.pixels.length);
      for (let i = 0; i < sum.length; i++) sum[i] += t.pixels[i];
    }
    if (gl.isContextLost()) throw new Error("the WebGL context was lost (the GPU process stopped)");
    const glError = gl.getError();
    if (glError !== gl.NO_ERROR) throw new Error(`WebGL error 0x${glError.toString(16)}`);
    if (sum === null) return base64(t.pixels);
    const out = new Float32Array(sum.length);
    for (let i = 0; i < sum.length; i++) out[i] = sum[i] / offsets.length;
    return base64(out);
  }
})();
