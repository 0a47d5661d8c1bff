// Writes the meshes of the npm packages `bunny` and `teapot` (simplicial complexes:
// {positions, cells}) as OBJ files, for the frontend's OBJ loader and the mesh tests.
//   node scripts/npm_mesh_to_obj.js <node_modules folder> <output folder>
'use strict';
const fs = require('fs');
const path = require('path');

const [modules, out] = process.argv.slice(2);
if (!modules || !out) {
  console.error('usage: node npm_mesh_to_obj.js <node_modules folder> <output folder>');
  process.exit(2);
}
fs.mkdirSync(out, { recursive: true });
for (const name of ['bunny', 'teapot']) {
  const mesh = require(path.resolve(modules, name));
  const lines = [`# ${name} from the npm package '${name}' (public domain), ${mesh.cells.length} triangles`];
  for (const p of mesh.positions) lines.push(`v ${p[0]} ${p[1]} ${p[2]}`);
  for (const c of mesh.cells) lines.push(`f ${c[0] + 1} ${c[1] + 1} ${c[2] + 1}`);
  // Written whole, then renamed: an interrupted run leaves no partial mesh behind.
  const target = path.join(out, `${name}.obj`);
  fs.writeFileSync(target + '.partial', lines.join('\n') + '\n');
  fs.renameSync(target + '.partial', target);
  console.log(`setup: wrote ${target} (${mesh.positions.length} vertices, ${mesh.cells.length} triangles)`);
}
