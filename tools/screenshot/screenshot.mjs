// Drives a headless Chromium already listening on --remote-debugging-port (DevTools protocol):
// opens the screenshot page, waits until the page has written its result into #out (the frame
// as a PNG data URL, or "error: ..."), and writes the PNG. Used by scripts/webgpu-screenshot.sh.
//
//   node tools/screenshot/screenshot.mjs PORT URL OUT.png
import { writeFileSync } from 'node:fs';
import CDP from 'chrome-remote-interface';

const [port, url, output] = process.argv.slice(2);
if (!port || !url || !output) {
  process.stderr.write('usage: node screenshot.mjs PORT URL OUT.png\n');
  process.exit(2);
}

let client;
try {
  client = await CDP({ port: Number(port) });
  const { Page, Runtime } = client;
  await Page.enable();
  await Page.navigate({ url });
  await Page.loadEventFired();
  // The page's module works asynchronously (WebGPU): wait, in the page, for #out to leave "pending".
  const { result, exceptionDetails } = await Runtime.evaluate({
    expression: `new Promise((resolve) => {
      const out = document.getElementById('out');
      const done = () => out && !out.textContent.startsWith('pending');
      if (done()) return resolve(out.textContent);
      const deadline = setTimeout(() => resolve('error: the page did not finish within 60 s (' + (out ? out.textContent : 'no #out') + ')'), 60000);
      new MutationObserver(() => { if (done()) { clearTimeout(deadline); resolve(out.textContent); } })
        .observe(out, { childList: true, characterData: true, subtree: true });
    })`,
    awaitPromise: true,
    returnByValue: true,
  });
  if (exceptionDetails) throw new Error(exceptionDetails.text);
  const text = String(result.value);
  const prefix = 'data:image/png;base64,';
  if (!text.startsWith(prefix)) throw new Error(text.replace(/^error: /, ''));
  writeFileSync(output, Buffer.from(text.slice(prefix.length), 'base64'));
} catch (e) {
  process.stderr.write(`screenshot.mjs: ${String(e.message).replace(/\s*\n\s*/g, ' ')}\n`);
  process.exitCode = 1;
} finally {
  await client?.close();
}
