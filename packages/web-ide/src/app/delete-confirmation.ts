/**
 * What the confirmation of a delete in the Explorer says (docs/ide.md "Deleting a generated file",
 * "Deleting a folder"): a file is deleted from disk, and a generated file holding user code in
 * protected regions says which regions and whether the next generation restores them; a folder
 * says how many files it holds and, the same way, its generated files holding code.
 */
import { api } from '../api.js';
import { REGION_COPY_NAME, SRC_GEN_DIR } from '@contract-studio/conventions';

const GENERATED = new RegExp(`(^|/)${SRC_GEN_DIR}/generated/`);
/** A generated file's path: group 1 is the folder holding its src-gen (none at the workspace root). */
const SRC_GEN_OF = new RegExp(`^(?:(.*)/)?${SRC_GEN_DIR}/generated/`);
const COPY = `${SRC_GEN_DIR}/${REGION_COPY_NAME}`;
/** The generated files holding code a folder's confirmation names one by one; the rest are counted. */
const LISTED = 5;

const plural = (n: number, one: string, many = `${one}s`) => `${n.toLocaleString('en-US')} ${n === 1 ? one : many}`;
const regionsOf = (held: { regions: string[] }) => `${plural(held.regions.length, 'protected region')} (${held.regions.join(', ')})`;

/**
 * What deleting file `path` does: deleted from disk; for a generated file whose regions hold code,
 * how many and which, and whether the next generation restores them from the last generation's copy.
 */
export async function deleteFileDetail(path: string): Promise<string> {
  const gone = 'The file will be deleted from disk.';
  if (!GENERATED.test(path)) return gone;
  const held = await api.userCode(path).catch(() => undefined);
  if (!held || held.regions.length === 0) return gone;
  return held.restorable
    ? `${gone} It is a generated file holding your code in ${regionsOf(held)}: the next generation (Generate All, a build, contract generate) generates it again with that code restored from the last generation's copy (${COPY}). There is no other undo.`
    : `${gone} It is a generated file holding your code in ${regionsOf(held)}, which could not be recorded: the next generation generates it with the defaults, and that code is lost unless you restore the file from git.`;
}

/**
 * What deleting folder `folder` does: everything in it deleted from disk, how many files; its
 * generated files holding code in protected regions (the first few named with their regions), and
 * whether the next generation restores that code — not when the folder takes their tree's copy of
 * it along (a project's `src-gen/` or the project itself). When the server cannot say, the
 * confirmation says only that everything in it is deleted.
 */
export async function deleteFolderDetail(folder: string): Promise<string> {
  const contents = await api.folderContents(folder).catch(() => undefined);
  const gone = 'The folder and everything in it will be deleted from disk';
  if (!contents) return `${gone}.`;
  const count = contents.files === 0 && !contents.cut ? 'it holds no file' : `${contents.cut ? 'at least ' : ''}${plural(contents.files, 'file')}`;
  const held = contents.userCode;
  if (held.length === 0) return `${gone}: ${count}.`;
  const said = [`${gone}: ${count}.`];
  const named = held.slice(0, LISTED).map((h) => `${h.path.slice(folder.length + 1)} (${h.regions.join(', ')})`).join('; ');
  const more = held.length > LISTED ? `; and ${plural(held.length - LISTED, 'other')}` : '';
  said.push(held.length === 1
    ? `One of them is a generated file holding your code in protected regions: ${named}.`
    : `${held.length.toLocaleString('en-US')} of them are generated files holding your code in protected regions: ${named}${more}.`);
  const restorable = held.filter((h) => h.restorable).length;
  const lost = held.filter((h) => !h.restorable);
  const them = (n: number) => (n === held.length ? (n === 1 ? 'it' : 'them') : `${n.toLocaleString('en-US')} of them`);
  if (restorable > 0) said.push(`The next generation (Generate All, a build, contract generate) generates ${them(restorable)} again with that code restored from the last generation's copy (${COPY}).`);
  if (lost.length > 0) {
    // the folder is a project's src-gen (or holds it): the copy of that code goes with it
    const copyGoes = lost.every((h) => { const srcGen = srcGenOf(h.path); return srcGen === folder || srcGen.startsWith(`${folder}/`); });
    const whose = lost.length === held.length ? 'That code' : `The code of ${them(lost.length)}`;
    said.push(copyGoes
      ? `${whose} is lost unless you restore the files from git: the last generation's copy of it (${COPY}) is deleted with the folder.`
      : `${whose} could not be recorded: the next generation generates the files with the defaults, and it is lost unless you restore them from git.`);
  }
  said.push('There is no other undo.');
  return said.join(' ');
}

/** The src-gen folder of a generated file's path (`robot/src-gen` of `robot/src-gen/generated/...`). */
function srcGenOf(path: string): string {
  const m = SRC_GEN_OF.exec(path);
  return m?.[1] ? `${m[1]}/${SRC_GEN_DIR}` : SRC_GEN_DIR;
}
