// Drives the web viewer through its own handlers, as a user would (tests/web/suite.sh evaluates this
// in the page through tests/web/cdp.py, in real time). The steps: a drag (pointer down, two moves:
// the frames while it moves must be coarse), release, a wheel notch towards the screen, an arrow key;
// then the fine frame at rest, read back from the canvas as base64 RGBA, with the view the page ended at.
(async () => {
  const m = await window.modelc.ready;
  const canvas = document.getElementById('view');
  const nextFrame = (n) => new Promise((resolve) => {
    const poll = () => (m.frames() > n ? resolve(m.last()) : setTimeout(poll, 5));
    poll();
  });
  const pointer = (type, x, y, buttons) => canvas.dispatchEvent(new PointerEvent(type, {
    clientX: x, clientY: y, pointerId: 1, isPrimary: true, pointerType: 'mouse', buttons: buttons, bubbles: true }));
  const first = await m.idle();

  let n = m.frames();
  pointer('pointerdown', 100, 100, 1);
  pointer('pointermove', 137, 91, 1);
  const moving1 = await nextFrame(n);
  n = m.frames();
  pointer('pointermove', 149, 95, 1);
  const moving2 = await nextFrame(n);
  pointer('pointerup', 149, 95, 0);
  canvas.dispatchEvent(new WheelEvent('wheel', { deltaY: -120, bubbles: true, cancelable: true }));
  window.dispatchEvent(new KeyboardEvent('keydown', { key: 'ArrowRight', bubbles: true, cancelable: true }));
  const rest = await m.idle();

  const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
  let bin = '';
  for (let i = 0; i < data.length; i += 8192) bin += String.fromCharCode.apply(null, data.subarray(i, i + 8192));
  return { first: first, moving: [moving1, moving2], rest: rest, view: m.view(),
           width: canvas.width, height: canvas.height, rgba: btoa(bin) };
})()
