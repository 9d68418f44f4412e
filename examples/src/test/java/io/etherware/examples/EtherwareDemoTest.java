package io.etherware.examples;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.PrintWriter;
import java.io.StringWriter;
import org.junit.jupiter.api.Test;
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
    void shouldNameTheOptionAndItsRangeWhenTheDurationIsOutOfRange() {
        assertEquals(2, execute("stress", "--duration", "0.5"));
        assertTrue(err.toString().contains("--duration=0.5 is out of range"), err.toString());
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
        assertEquals(2, execute("bench", "--duration-s", "0"));
        assertTrue(err.toString().contains("--duration-s=0.0 is out of range"), err.toString());
    }

    @Test
    void shouldRefuseQuickWithADuration() {
        assertEquals(2, execute("bench", "--quick", "--duration-s", "20"));
        assertTrue(err.toString().contains("--duration-s=20.0 with --quick"), err.toString());
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
