package io.etherware.rt.scheduling;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

import io.etherware.rt.platform.OsThreadStat;
import io.etherware.rt.platform.Platform;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * The platform as a node sees it at start, in a fresh JVM (the once-per-kind warnings are per
 * JVM): refused without privileges, granted with them, and in both cases the node runs its HIGH
 * message and logs one {@code PlatformReport} line per dispatcher when it starts.
 */
class PlatformRefusalChildJvmIT {

    private static final Path SETPRIV = Path.of("/usr/bin/setpriv");
    private static final Path PRLIMIT = Path.of("/usr/bin/prlimit");

    private record Run(int exitCode, List<String> out, List<String> err) {
        List<String> prefixed(String prefix) {
            return out.stream().filter(line -> line.startsWith(prefix)).map(line -> line.substring(prefix.length()))
                    .toList();
        }

        long warnings(String containing) {
            return err.stream().filter(line -> line.contains(" WARN ") && line.contains(containing)).count();
        }

        /** The scheduler's INFO log lines at node start, without the logger's prefix. */
        List<String> startLog() {
            String prefix = "INFO " + RealtimeScheduler.class.getName() + " - scheduler rt@probe: ";
            return err.stream().filter(line -> line.contains(prefix))
                    .map(line -> line.substring(line.indexOf(prefix) + prefix.length())).toList();
        }
    }

    @Test
    void shouldWarnOncePerKindWithErrnoAndFixAndStillRunWhenCapabilitiesAreDropped() throws Exception {
        assumeTrue(Platform.current().isAvailable() && Files.isExecutable(SETPRIV) && Files.isExecutable(PRLIMIT),
                "needs Linux with setpriv and prlimit (util-linux)");
        // No CAP_SYS_NICE, no CAP_IPC_LOCK, RLIMIT_RTPRIO 0 and a 64 KiB RLIMIT_MEMLOCK: how an
        // unprivileged user or a default container starts.
        Run run = runProbe(List.of(SETPRIV.toString(), "--inh-caps=-sys_nice,-ipc_lock",
                "--bounding-set=-sys_nice,-ipc_lock", PRLIMIT.toString(), "--rtprio=0", "--memlock=65536"));

        assertEquals(0, run.exitCode(), String.join("\n", run.err()));
        assertEquals(List.of("HIGH on rt-dispatcher-1@probe"), run.prefixed("RAN "),
                "the node runs on without real-time priority");
        List<String> report = run.prefixed("REPORT ");
        assertEquals(6, report.size(), String.join("\n", report));
        assertTrue(report.get(0).contains("requested SCHED_OTHER") && report.get(0).contains("granted SCHED_OTHER"),
                report.get(0));
        for (int id = 1; id <= 3; id++) {
            String line = report.get(id);
            assertTrue(line.startsWith("rt-dispatcher-" + id), line);
            assertTrue(line.contains("granted SCHED_OTHER"), line);
            assertTrue(line.contains("refused: EPERM (errno 1)"), line);
        }
        assertTrue(report.get(4).startsWith("memory: requested mlockall"), report.get(4));
        assertTrue(report.get(4).contains("refused"), report.get(4));
        assertTrue(report.get(5).startsWith("cpu latency: "), "the CPU latency request is reported: " + report.get(5));
        assertEquals(1, run.warnings("thread priority"), "one warning for three refused dispatchers");
        assertEquals(1, run.warnings("EPERM (errno 1: Operation not permitted)"));
        assertEquals(1, run.warnings("setcap cap_sys_nice+ep"), "the warning says how to fix it");
        assertEquals(1, run.warnings("RLIMIT_RTPRIO (now soft=0, hard=0) to at least 80"),
                "the one warning quotes the most demanding dispatcher, whichever was refused first");
        assertEquals(1, run.warnings("memory lock"));
        assertEquals(List.of("0 kB"), run.prefixed("VMLCK "));
        assertLogsTheReportAtStart(run);
    }

    @Test
    void shouldGrantTableIIPrioritiesAndLockMemoryWhenPrivilegedElseReportRefusals() throws Exception {
        assumeTrue(Platform.current().isAvailable(), "needs Linux");
        Run run = runProbe(List.of());

        assertEquals(0, run.exitCode(), String.join("\n", run.err()));
        assertEquals(List.of("HIGH on rt-dispatcher-1@probe"), run.prefixed("RAN "));
        assertLogsTheReportAtStart(run);
        List<String> report = run.prefixed("REPORT ");
        if (OsThreadStat.hasCapSysNice() && OsThreadStat.hasCapability(14 /* CAP_IPC_LOCK */)) {
            assertTrue(report.get(1).contains("granted SCHED_FIFO/80"), report.get(1));
            assertTrue(report.get(2).contains("granted SCHED_FIFO/70"), report.get(2));
            assertTrue(report.get(3).contains("granted SCHED_FIFO/60"), report.get(3));
            assertTrue(report.get(4).endsWith("granted"), report.get(4));
            long lockedKb = Long.parseLong(run.prefixed("VMLCK ").getFirst().replace(" kB", ""));
            assertTrue(lockedKb > 1024, "locked " + lockedKb + " kB");
            assertEquals(0, run.warnings("refused"), String.join("\n", run.err()));
        } else {
            assertTrue(report.get(1).contains("granted SCHED_OTHER") && report.get(1).contains("refused"),
                    report.get(1));
            assertEquals(1, run.warnings("thread priority"));
        }
    }

    private static void assertLogsTheReportAtStart(Run run) {
        List<String> report = run.prefixed("REPORT ");
        List<String> logged = run.startLog();
        assertEquals(report, logged.subList(1, logged.size()), String.join("\n", run.err()));
        assertTrue(logged.getFirst().startsWith("placement criticality-deadline, 4 dispatchers"), logged.getFirst());
        for (int id = 0; id < 4; id++) {
            assertTrue(logged.get(1 + id).startsWith("rt-dispatcher-" + id + "@probe tid="), logged.get(1 + id));
            assertTrue(logged.get(1 + id).contains(": requested SCHED_"), logged.get(1 + id));
            assertTrue(logged.get(1 + id).contains(", granted SCHED_"), logged.get(1 + id));
        }
    }

    private static Run runProbe(List<String> wrapper) throws IOException, InterruptedException {
        var command = new ArrayList<>(wrapper);
        command.add(Path.of(System.getProperty("java.home"), "bin", "java").toString());
        command.addAll(List.of("-Xms32m", "-Xmx32m", "-XX:+UseSerialGC", "-XX:TieredStopAtLevel=1",
                "--enable-native-access=ALL-UNNAMED", "-cp",
                System.getProperty("surefire.test.class.path", System.getProperty("java.class.path")),
                SchedulerProbeMain.class.getName(), "lock"));
        Path out = Files.createTempFile("probe", ".out");
        Path err = Files.createTempFile("probe", ".err");
        try {
            Process process = new ProcessBuilder(command).redirectOutput(out.toFile()).redirectError(err.toFile())
                    .start();
            if (!process.waitFor(60, TimeUnit.SECONDS)) {
                process.destroyForcibly();
                throw new AssertionError("probe JVM did not finish within 60 s: " + command);
            }
            return new Run(process.exitValue(), Files.readAllLines(out), Files.readAllLines(err));
        } finally {
            Files.deleteIfExists(out);
            Files.deleteIfExists(err);
        }
    }
}
