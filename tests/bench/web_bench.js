// Times the web viewer's module in the page it ships in (tests/bench/web.sh evaluates this function,
// called with a size and a frame count, in the page through tests/web/cdp.py, in real time): after a
// warm-up of at least a turn and 3 s (Chromium compiles a module's hot functions fully only after
// they have run a while), F frames of a turn of yaw (frame i at i * 4096 / F, as the native viewer's
// --bench) at w x h, drawn by mcw_draw as the page draws them (clear, render, finish, RGBA), in
// batches of 10 frames timed with performance.now(). Returns the median over batches of a batch's
// time over its frames, and the points drawn per frame. With a style (1 shaded, 2 lines, 3
// shaded+lines), the bake's mesh part at its full level through mcw_draw_mesh instead, as the page
// draws it (the native viewer's --mode); then "points" counts the faces drawn (shaded) or the line
// pixels (lines) per frame.
(async (w, h, F, style) => {
  const m = await window.modelc.ready;
  const ex = m.exports();
  const B = 10, error = 16;
  const full = style ? ex.mcw_mesh_vertices() : 0;
  const frame = style ? (i) => ex.mcw_draw_mesh(w, h, Math.floor(i * 4096 / F), 0, 65536, style, full)
                      : (i) => ex.mcw_draw(w, h, Math.floor(i * 4096 / F), 0, 65536, error);
  const drawn = style === 2 ? () => ex.mcw_mesh_line_pixels() : style ? () => ex.mcw_mesh_drawn() : () => ex.mcw_drawn();
  const warm = performance.now();
  for (let i = 0; i < F || performance.now() - warm < 3000; i++) frame(i % F);
  const ms = [];
  let points = 0;
  for (let i = 0; i < F; i += B) {
    const t0 = performance.now();
    for (let k = i; k < i + B && k < F; k++) { if (frame(k) !== 0) throw new Error('frame ' + k + ' failed'); points += drawn(); }
    ms.push((performance.now() - t0) / Math.min(B, F - i));
  }
  ms.sort((a, b) => a - b);
  const mid = ms.length >> 1;
  return { ms: ms.length % 2 ? ms[mid] : (ms[mid - 1] + ms[mid]) / 2, points: Math.round(points / F) };
})
