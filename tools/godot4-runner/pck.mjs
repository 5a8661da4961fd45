// Godot 4's resource pack (.pck), format version 3 (Godot 4.4+), as the engine reads it
// (core/io/file_access_pack.cpp): a header, the files' bytes, then the directory at the end.
//   "GDPC" | u32 format 3 | u32 major, minor, patch | u32 flags | u64 file base | u64 directory
//   offset | 16 x u32 reserved | files (each padded to 16 bytes) | u32 count | per file: u32 path
//   length (padded to 4, NUL-filled), path (relative to res://), u64 offset from the file base,
//   u64 size, 16-byte MD5, u32 flags.
// Flag 2 (PACK_REL_FILEBASE): offsets count from the file base. Files are written sorted by
// path, so the same files give the same bytes.
import { createHash } from 'node:crypto';

const HEADER_BYTES = 0x70;
const GODOT_VERSION = [4, 6, 0];

export function packFiles(files) {
  const names = Object.keys(files).sort();
  const header = Buffer.alloc(HEADER_BYTES);
  header.write('GDPC', 0, 'latin1');
  header.writeUInt32LE(3, 4);
  GODOT_VERSION.forEach((v, i) => header.writeUInt32LE(v, 8 + 4 * i));
  header.writeUInt32LE(2, 20);
  header.writeBigUInt64LE(BigInt(HEADER_BYTES), 24);
  const blobs = [];
  const directory = [Buffer.alloc(4)];
  directory[0].writeUInt32LE(names.length);
  let offset = 0;
  for (const name of names) {
    const data = Buffer.from(files[name]);
    const pathBytes = Buffer.from(name, 'utf8');
    const paddedPath = Buffer.alloc((pathBytes.length + 4) & ~3);
    pathBytes.copy(paddedPath);
    const length = Buffer.alloc(4);
    length.writeUInt32LE(paddedPath.length, 0);
    const tail = Buffer.alloc(16);
    tail.writeBigUInt64LE(BigInt(offset), 0);
    tail.writeBigUInt64LE(BigInt(data.length), 8);
    directory.push(length, paddedPath, tail, createHash('md5').update(data).digest(), Buffer.alloc(4));
    const padding = (16 - (data.length % 16)) % 16;
    blobs.push(data, Buffer.alloc(padding));
    offset += data.length + padding;
  }
  header.writeBigUInt64LE(BigInt(HEADER_BYTES + offset), 32);
  return Buffer.concat([header, ...blobs, ...directory]);
}
