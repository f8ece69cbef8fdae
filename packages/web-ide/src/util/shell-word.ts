/** `word` as one POSIX shell word: as it is when it holds only `A-Z a-z 0-9 _ . / + , = : @ % -`, else in single quotes (a `'` in it written `'\''`). */
export function shellWord(word: string): string {
  return /^[A-Za-z0-9_./+,=:@%-]+$/.test(word) ? word : `'${word.replace(/'/g, `'\\''`)}'`;
}
