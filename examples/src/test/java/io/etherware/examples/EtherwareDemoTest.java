package io.etherware.examples;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeFalse;

import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import picocli.CommandLine;

/** The command line's parsing and errors; no scenario runs here (a bad option stops it first). */
class EtherwareDemoTest {

    private final StringWriter out = new StringWriter();
    private final StringWriter err = new StringWriter();

    private int execute(String... args) {
        CommandLine commandLine = EtherwareDemo.commandLine();
        commandLine.setOut(new PrintWriter(out, true));
        commandLine.setErr(new PrintWriter(err, true));
        return commandLine.execute(args);
    }

    @Test
    void shouldListTheCommonOptionsInTheStressHelp() {
        assertEquals(0, execute("stress", "--help"));
        String help = out.toString();
        for (String option : new String[] {"--duration", "--period-ms", "--out", "--help", "--stress-every",
            "--stress-ms", "--load-threads", "--only"}) {
            assertTrue(help.contains(option), () -> option + " missing from:\n" + help);
        }
        assertTrue(help.contains("Section VI-B"), help);
    }

    @Test
    void shouldListTheStressOptionsAndTheNode2OffsetInTheNetstressHelp() {
        assertEquals(0, execute("netstress", "--help"));
        String help = out.toString();
        for (String option : new String[] {"--duration", "--period-ms", "--out", "--stress-every", "--stress-ms",
            "--load-threads", "--only", "--node2-offset"}) {
            assertTrue(help.contains(option), () -> option + " missing from:\n" + help);
        }
    }

    @Test
    void shouldRefuseANode2OffsetOfAWholeStressPeriod() {
        assertEquals(2, execute("netstress", "--stress-every", "4", "--node2-offset", "4"));
        assertTrue(err.toString().contains("--node2-offset=4.0 is out of range"), err.toString());
    }

    @Test
    void shouldAskForAScenarioWhenNoneIsNamed() {
        assertEquals(2, execute());
        assertTrue(err.toString().contains("Name a scenario: stress, netstress, upgrade, migrate, bench"), err.toString());
    }

    @Test
    void shouldNameTheOptionAndItsRangeWhenTheMigrationLeavesTooLittleTimeOnANode() {
        assertEquals(2, execute("migrate", "--duration", "10", "--migrate-at", "9"));
        assertTrue(err.toString().contains("--migrate-at=9.0 is out of range"), err.toString());
    }

    @Test
    void shouldNameTheOptionAndItsMinimumWhenTheDurationIsTooShort() {
        assertEquals(2, execute("stress", "--duration", "0.5"));
        assertTrue(err.toString().contains("--duration 0.5: must be at least 1 s for a stress run"), err.toString());
    }

    @Test
    void shouldRefuseAMigrateRunTooShortInOptionTermsAndSayWhy() {
        assertEquals(2, execute("migrate", "--duration", "2"));
        assertTrue(err.toString().contains("--duration 2: must be at least 4 s for a migrate run (2 s on node 2 before"
                + " the migration and as much on node 1 after it)"), err.toString());
        assertFalse(err.toString().contains("durationNs"), err.toString());
    }

    @Test
    void shouldRefuseAnUpgradeRunTooShortAsAUsageError() {
        assertEquals(2, execute("upgrade", "--duration", "1.5"));
        assertTrue(err.toString().contains("--duration 1.5: must be at least 2 s for an upgrade run (1 s of V1"),
                err.toString());
    }

    @Test
    void shouldStateEachScenariosDefaultAndMinimumDurationInItsHelp() {
        for (String[] scenario : new String[][] {{"stress", "20", "1"}, {"netstress", "20", "1"},
            {"upgrade", "60", "2"}, {"migrate", "60", "4"}}) {
            out.getBuffer().setLength(0);
            assertEquals(0, execute(scenario[0], "--help"));
            String help = out.toString().replaceAll("\\s+", " ");
            assertTrue(help.contains("--duration=SECONDS Length of each run in seconds (default: " + scenario[1]
                    + "; at least " + scenario[2]), () -> scenario[0] + ":\n" + help);
        }
    }

    /**
     * An unusable --out, on every command that takes one. Each command line also has a bad value of
     * an option checked after the output directory, so a command that did not check --out before
     * running stops there with another error instead of running a scenario.
     */
    @Test
    void shouldRefuseAnOutThatIsAFileBeforeRunningOnEveryCommand(@TempDir Path dir) throws Exception {
        Path file = Files.createFile(dir.resolve("results.txt"));
        for (String[] args : commandsWithOut(file.toString(), dir)) {
            err.getBuffer().setLength(0);
            assertEquals(2, execute(args), () -> String.join(" ", args) + ":\n" + err);
            assertTrue(err.toString().contains("--out " + file + ": is a file, not a directory"),
                    () -> String.join(" ", args) + ":\n" + err);
        }
    }

    @Test
    void shouldRefuseAnOutThroughAFileAndNameTheFile(@TempDir Path dir) throws Exception {
        Path file = Files.createFile(dir.resolve("results.txt"));
        Path through = file.resolve("stress");
        for (String[] args : commandsWithOut(through.toString(), dir)) {
            err.getBuffer().setLength(0);
            assertEquals(2, execute(args), () -> String.join(" ", args) + ":\n" + err);
            assertTrue(err.toString().contains("--out " + through + ": goes through " + file + ", which is a file"),
                    () -> String.join(" ", args) + ":\n" + err);
        }
    }

    @Test
    void shouldRefuseAnOutThatCannotBeWritten(@TempDir Path dir) throws Exception {
        Path locked = Files.createDirectory(dir.resolve("locked"),
                PosixFilePermissions.asFileAttribute(PosixFilePermissions.fromString("r-xr-xr-x")));
        try {
            assumeFalse(Files.isWritable(locked), "running as root: every directory is writable");
            for (String[] args : commandsWithOut(locked.toString(), dir)) {
                err.getBuffer().setLength(0);
                assertEquals(2, execute(args), () -> String.join(" ", args) + ":\n" + err);
                assertTrue(err.toString().contains("--out " + locked + ": the directory is not writable"),
                        () -> String.join(" ", args) + ":\n" + err);
            }
        } finally {
            Files.setPosixFilePermissions(locked, PosixFilePermissions.fromString("rwxr-xr-x"));
        }
    }

    /** stress, netstress, upgrade, migrate and bench with {@code --out out} and a bad option checked after it. */
    private static String[][] commandsWithOut(String out, Path dir) throws Exception {
        String jar = Files.createFile(dir.resolve("x-controller-v2.jar")).toString();
        return new String[][] {
            {"stress", "--out", out, "--baud", "1"},
            {"netstress", "--out", out, "--baud", "1"},
            {"upgrade", "--jar", jar, "--out", out, "--baud", "1"},
            {"migrate", "--out", out, "--baud", "1"},
            {"bench", "--out", out, "--repetitions", "1"}};
    }

    @Test
    void shouldNameTheOptionWhenThePeriodIsOutOfRange() {
        assertEquals(2, execute("stress", "--period-ms", "0"));
        assertTrue(err.toString().contains("--period-ms=0 is out of range"), err.toString());
    }

    @Test
    void shouldRefuseAStressLongerThanItsPeriod() {
        assertEquals(2, execute("stress", "--stress-every", "1", "--stress-ms", "1500"));
        assertTrue(err.toString().contains("--stress-ms=1500 is out of range"), err.toString());
    }

    @Test
    void shouldRefuseAnUnknownRunName() {
        assertEquals(2, execute("stress", "--only", "edf"));
        assertTrue(err.toString().contains("--only"), err.toString());
    }

    @Test
    void shouldListTheUpgradesOptionsInItsHelp() {
        assertEquals(0, execute("upgrade", "--help"));
        String help = out.toString();
        for (String option : new String[] {"--duration", "--period-ms", "--out", "--upgrade-at", "--jar"}) {
            assertTrue(help.contains(option), () -> option + " missing from:\n" + help);
        }
    }

    @Test
    void shouldNameTheJarOptionWhenThePluginIsMissing() {
        assertEquals(2, execute("upgrade", "--jar", "/nonexistent/controller-v2.jar"));
        assertTrue(err.toString().contains("--jar=/nonexistent/controller-v2.jar is not a file"), err.toString());
    }

    @Test
    void shouldRefuseAnUpgradeTooCloseToTheEnd(@org.junit.jupiter.api.io.TempDir java.nio.file.Path dir)
            throws Exception {
        java.nio.file.Path jar = java.nio.file.Files.createFile(dir.resolve("x-controller-v2.jar"));
        assertEquals(2, execute("upgrade", "--jar", jar.toString(), "--duration", "10", "--upgrade-at", "9.5"));
        assertTrue(err.toString().contains("--upgrade-at=9.5 is out of range"), err.toString());
    }

    @Test
    void shouldRefuseANonNumericDuration() {
        assertEquals(2, execute("stress", "--duration", "ten"));
        assertTrue(err.toString().contains("--duration") && err.toString().contains("ten"), err.toString());
    }

    @Test
    void shouldNameTheBenchDurationWhenItIsOutOfRange() {
        assertEquals(2, execute("bench", "--duration", "0"));
        assertTrue(err.toString().contains("--duration=0.0 is out of range"), err.toString());
    }

    @Test
    void shouldTakeTheBenchsOldDurationNameWithoutShowingIt() {
        assertEquals(2, execute("bench", "--duration-s", "0"));
        assertTrue(err.toString().contains("--duration=0.0 is out of range"), err.toString());
        err.getBuffer().setLength(0);
        assertEquals(2, execute("bench", "--duration-s", "20", "--duration", "30"));
        assertTrue(err.toString().contains("--duration-s is the old name of --duration: give one"), err.toString());
        assertEquals(0, execute("bench", "--help"));
        assertTrue(out.toString().contains("--duration=SECONDS") && !out.toString().contains("--duration-s"),
                out.toString());
    }

    @Test
    void shouldRefuseQuickWithADuration() {
        assertEquals(2, execute("bench", "--quick", "--duration", "20"));
        assertTrue(err.toString().contains("--duration=20.0 with --quick"), err.toString());
    }

    @Test
    void shouldNameTheSectionWhenItIsOutOfRange() {
        assertEquals(2, execute("bench", "--quick", "--section", "2,9"));
        assertTrue(err.toString().contains("--section=9 is out of range"), err.toString());
    }

    @Test
    void shouldNameTheRepetitionsWhenTooFew() {
        assertEquals(2, execute("bench", "--repetitions", "2"));
        assertTrue(err.toString().contains("--repetitions=2 is out of range"), err.toString());
    }
}
