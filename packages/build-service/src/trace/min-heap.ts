/**
 * A binary min-heap under a caller's order: the k-way merge of a run's logs (parse.ts in memory,
 * the CLI's streamed `contract trace`) keeps its files, or one file's records, in one.
 */
export class MinHeap<T> {
    private readonly items: T[] = [];

    /** `before(a, b)`: a comes out first. */
    constructor(private readonly before: (a: T, b: T) => boolean) {}

    get size(): number {
        return this.items.length;
    }

    peek(): T | undefined {
        return this.items[0];
    }

    push(item: T): void {
        const items = this.items;
        let i = items.push(item) - 1;
        while (i > 0) {
            const parent = (i - 1) >> 1;
            if (!this.before(items[i]!, items[parent]!)) break;
            [items[i], items[parent]] = [items[parent]!, items[i]!];
            i = parent;
        }
    }

    pop(): T | undefined {
        const items = this.items;
        const top = items[0];
        const last = items.pop();
        if (items.length && last !== undefined) {
            items[0] = last;
            this.down(0);
        }
        return top;
    }

    /** After the top item's order changed (its file's next record): puts it back in place. */
    topChanged(): void {
        if (this.items.length) this.down(0);
    }

    private down(i: number): void {
        const items = this.items;
        for (;;) {
            const l = 2 * i + 1;
            const r = l + 1;
            let m = i;
            if (l < items.length && this.before(items[l]!, items[m]!)) m = l;
            if (r < items.length && this.before(items[r]!, items[m]!)) m = r;
            if (m === i) return;
            [items[i], items[m]] = [items[m]!, items[i]!];
            i = m;
        }
    }
}
