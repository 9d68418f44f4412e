package io.etherware.examples.scenario;

import static org.junit.jupiter.api.Assertions.assertEquals;

import java.util.List;
import org.junit.jupiter.api.Test;

class NodeProcessTest {

    @Test
    void shouldGiveTheNodeTheCollectorAndHeapOptionsAndItsOwnLogFileOnly() {
        List<String> options = List.of("--enable-native-access=ALL-UNNAMED", "-XX:+UseZGC", "-Xms1g", "-Xmx1g",
                "-XX:+AlwaysPreTouch", "-Xlog:gc:file=gc.log", "-Xlog:safepoint:file=jvm-%p.log",
                "-agentlib:jdwp=transport=dt_socket", "-Dx=y", "-XX:+UnlockDiagnosticVMOptions",
                "-XX:MaxGCPauseMillis=5");
        assertEquals(List.of("-XX:+UseZGC", "-Xms1g", "-Xmx1g", "-XX:+AlwaysPreTouch",
                        "-Xlog:safepoint:file=jvm-%p.log", "-XX:MaxGCPauseMillis=5"),
                NodeProcess.nodeJvmOptions(options));
    }
}
