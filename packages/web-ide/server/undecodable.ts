/**
 * Files whose bytes are not UTF-8 (a Latin-1 `café` in a comment, a binary). The editor works on
 * text: such a file is decoded with U+FFFD for each byte it cannot read, and a save of that text
 * would write U+FFFD over the user's bytes — in every region, the ones not touched too. So
 * GET /api/file says where the first such byte is (the tab opens read-only), and PUT /api/file
 * refuses to write over such a file a text that differs from its bytes (file-api.ts,
 * guarded-write.ts). `contract generate` keeps those bytes as they are (codegen).
 */
import { isUtf8 } from 'node:buffer';

/** The 1-based line of the first byte of `bytes` that is not UTF-8, or undefined when all are. */
export function undecodableLine(bytes: Buffer): number | undefined {
  if (isUtf8(bytes)) return undefined;
  const text = bytes.toString('utf8');
  const at = text.indexOf('\uFFFD');
  let line = 1;
  for (let i = text.indexOf('\n'); i >= 0 && i < at; i = text.indexOf('\n', i + 1)) line++;
  return line;
}

/** Why a save over `rel`, whose bytes are not UTF-8 from line `line` on, is refused. */
export function undecodableRefusal(rel: string, line: number): string {
  return `${rel} holds bytes that are not UTF-8 (line ${line}: Latin-1 or binary): the editor shows each as \uFFFD and a save would write that over them, in every region; ` +
    `nothing was written. Convert the file to UTF-8 (iconv -f latin1 -t utf-8), or edit it in an editor that keeps its encoding`;
}
