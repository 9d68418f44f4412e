package io.etherware.examples.bench;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.examples.EtherwareDemo;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import java.util.function.Function;
import java.util.stream.Collectors;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import picocli.CommandLine;

/**
 * The bench's smoke run ({@code bench --quick}, about 30 s), so the harness cannot rot: every row
 * is there, in the markdown and in the JSON, with sane values. No figure is held to a target: on a
 * shared machine the figures of a 30-second run say nothing; the README's come from a full run.
 */
class BenchCommandIT {

    /** Every row the report must have, by id. */
    private static final List<String> ROW_IDS = List.of(
            "periodic.notifier.idle", "periodic.notifier-park.idle", "periodic.executor.idle", "periodic.cyclictest.idle",
            "periodic.notifier.loaded", "periodic.notifier-park.loaded", "periodic.executor.loaded", "periodic.cyclictest.loaded",
            "dispatch.fifo.idle", "dispatch.fifo.flood", "dispatch.rt.idle", "dispatch.rt.flood",
            "dispatch.rt-pinned.idle", "dispatch.rt-pinned.flood", "dispatch.queue.idle", "dispatch.queue.flood",
            "throughput.fifo", "throughput.rt", "throughput.queue", "alloc.local-send", "alloc.tick",
            "codec.xml.encode.tick", "codec.json.encode.tick", "codec.xml.decode.tick", "codec.json.decode.tick",
            "codec.xml.encode.angles", "codec.json.encode.angles", "codec.xml.decode.angles",
            "codec.json.decode.angles",
            "loopback.messenger", "loopback.raw", "loopback.raw.hand-offs", "loopback.raw.hand-offs.codec",
            "loopback.ratio.p50", "loopback.ratio.p99",
            "loopback.messenger.high-under-low", "loopback.messenger.high-under-low.one-lane", "loopback.messenger.rt-idle",
            "loopback.one-way.high", "loopback.one-way.none-after-high",
            "gap.upgrade", "gap.migration",
            "gc.pauses");

    @Test
    void shouldWriteEveryRowWithSaneValuesInAQuickRun(@TempDir Path out) throws Exception {
        var stdout = new StringWriter();
        var stderr = new StringWriter();
        CommandLine commandLine = EtherwareDemo.commandLine();
        commandLine.setOut(new PrintWriter(stdout, true));
        commandLine.setErr(new PrintWriter(stderr, true));

        assertEquals(0, commandLine.execute("bench", "--quick", "--out", out.toString()), stderr::toString);

        String markdown = Files.readString(out.resolve(BenchReport.MARKDOWN_FILE));
        BenchReport report = BenchReport.read(out.resolve(BenchReport.JSON_FILE));
        assertEquals(markdown, report.markdown(), "the JSON holds what the markdown shows");
        assertTrue(stdout.toString().contains(markdown), "the table is printed too");
        Map<String, BenchRow> rows = report.rows().stream()
                .collect(Collectors.toMap(BenchRow::id, Function.identity()));
        assertEquals(ROW_IDS.stream().sorted().toList(), rows.keySet().stream().sorted().toList());
        for (String id : ROW_IDS) {
            BenchRow row = rows.get(id);
            assertTrue(markdown.contains("| " + row.section() + " | " + row.variant() + " | " + row.condition() + " |"),
                    () -> id + " missing from the markdown:\n" + markdown);
            if (id.startsWith("periodic.cyclictest") && !row.measured()) {
                assertTrue(row.note().contains("not installed") || row.note().contains("failed"), row::note);
                continue;
            }
            assertTrue(row.measured(), () -> id + " not measured: " + row.note());
            Percentiles p = row.percentiles();
            if (p.count() > 0) {
                assertTrue(p.p50Ns() > 0 && p.p50Ns() <= p.p99Ns() && p.p99Ns() <= p.p999Ns()
                        && p.p999Ns() <= p.maxNs(), () -> id + ": " + p);
            } else {
                assertTrue(Double.isFinite(row.value()) && row.value() >= 0, () -> id + ": " + row);
            }
        }
        assertTrue(rows.get("throughput.rt").value() > 0 && rows.get("throughput.queue").value() > 0);
        assertTrue(rows.get("codec.xml.decode.angles").value() > 0, "codec ns/op");
        assertTrue(rows.get("dispatch.rt.flood").percentiles().count() > 0);
        assertTrue(rows.get("gap.upgrade").note().contains("0 breaks"), rows.get("gap.upgrade")::note);
        assertTrue(rows.get("gap.migration").note().contains("0 breaks"), rows.get("gap.migration")::note);
        assertTrue(report.machine().cores() > 0 && !report.machine().jdk().isBlank()
                && !report.machine().sched().isBlank());
        assertTrue(report.machine().jvmOptions().stream().anyMatch(option -> option.startsWith("--enable-native-access")),
                () -> "JVM options: " + report.machine().jvmOptions());
    }
}
