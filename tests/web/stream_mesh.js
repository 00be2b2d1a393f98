// The stream page of a mesh bake (tests/web/stream.sh evaluates this in a page opened with
// ?mode=...&lod=...[&stream=...]): waits until the stream has ended, complete or not, then reads the
// frame at rest back from the canvas as base64 RGBA, with the stream's state and the level drawn.
(async () => {
  const m = await window.modelc.ready;
  const st = await m.received;
  const rest = await m.idle();
  const canvas = document.getElementById('view');
  const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
  let bin = '';
  for (let i = 0; i < data.length; i += 8192) bin += String.fromCharCode.apply(null, data.subarray(i, i + 8192));
  return { width: canvas.width, height: canvas.height, stream: st, rest: rest, view: m.view(),
           status: document.getElementById('status').textContent, rgba: btoa(bin) };
})()
