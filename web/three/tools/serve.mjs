// A static file server for the example and the test: serves web/three/ (the package, its
// node_modules and generated/) on 127.0.0.1, and further folders under their own prefixes.
//   node tools/serve.mjs [PORT]     then open http://127.0.0.1:PORT/example/
import { readFile } from 'node:fs/promises';
import { createServer } from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const packageRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');

const TYPES = {
  '.html': 'text/html',
  '.js': 'text/javascript',
  '.mjs': 'text/javascript',
  '.json': 'application/json',
  '.png': 'image/png',
  '.glb': 'model/gltf-binary',
  '.gltf': 'model/gltf+json',
};

// mounts: { '/prefix': '/absolute/folder' } served besides the package.
export function serve(port = 0, mounts = {}) {
  const server = createServer(async (request, response) => {
    let pathname = decodeURIComponent(new URL(request.url, 'http://x').pathname);
    if (pathname.endsWith('/')) pathname += 'index.html';
    let root = packageRoot;
    for (const [prefix, folder] of Object.entries(mounts)) {
      if (pathname.startsWith(prefix + '/')) {
        root = folder;
        pathname = pathname.slice(prefix.length);
        break;
      }
    }
    const file = path.join(root, pathname);
    if (!file.startsWith(root + path.sep)) {
      response.writeHead(403).end();
      return;
    }
    try {
      const body = await readFile(file);
      response.writeHead(200, { 'Content-Type': TYPES[path.extname(file)] || 'application/octet-stream' }).end(body);
    } catch {
      response.writeHead(404).end();
    }
  });
  return new Promise((resolve) => server.listen(port, '127.0.0.1', () => resolve(server)));
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const server = await serve(Number(process.argv[2] || 8019));
  console.log(`glint-three: serving ${packageRoot} at http://127.0.0.1:${server.address().port}/example/`);
}
