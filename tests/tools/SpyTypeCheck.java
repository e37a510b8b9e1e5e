// Decodes every event of an LCM log with the types lcm-spy finds on the class path: lcm-spy's own
// lcm.spy.LCMTypeDatabase (the class discovery it runs at start, keyed by fingerprint), then each
// type's byte[] constructor, as lcm-spy does for a message it shows. Prints one line per channel
// and type ("<channel> <class>: <count>"), the vehicle state count and the first and last
// position, in the text format of scripts/read_lcm_log.py, so the two decoders can be compared.
// Exit 1 when an event has no type on the class path or does not decode.
// Usage: java -cp lcm.jar:a3lcm-types.jar:. SpyTypeCheck LOG
import java.io.ByteArrayInputStream;
import java.io.DataInputStream;
import java.io.EOFException;
import java.io.IOException;
import java.util.Map;
import java.util.TreeMap;

import lcm.logging.Log;
import lcm.spy.LCMTypeDatabase;

public class SpyTypeCheck {
  private final LCMTypeDatabase types = new LCMTypeDatabase();
  private final Map<String, Integer> counts = new TreeMap<>();
  private int failures = 0;
  private int vehicleStates = 0;
  private Object firstState = null;
  private Object lastState = null;

  public static void main(String[] args) throws Exception {
    if (args.length != 1) {
      System.err.println("usage: SpyTypeCheck LOG");
      System.exit(2);
    }
    SpyTypeCheck check = new SpyTypeCheck();
    check.readLog(args[0]);
    check.print(args[0]);
    System.exit(check.failures == 0 ? 0 : 1);
  }

  private void readLog(String path) throws IOException {
    Log log = new Log(path, "r");
    try {
      while (true) decode(log.readNext());
    } catch (EOFException end) {
      log.close();
    }
  }

  private void decode(Log.Event event) {
    try {
      long fingerprint = new DataInputStream(new ByteArrayInputStream(event.data)).readLong();
      Class<?> type = types.getClassByFingerprint(fingerprint);
      if (type == null) {
        fail(event.channel + ": no LCM type on the class path has fingerprint 0x" + Long.toHexString(fingerprint));
        return;
      }
      Object message = type.getConstructor(byte[].class).newInstance((Object) event.data);
      counts.merge(event.channel + " " + type.getSimpleName(), 1, Integer::sum);
      if (type.getName().equals("a3lcm.vehicle_state_t")) {
        if (firstState == null) firstState = message;
        lastState = message;
        ++vehicleStates;
      }
    } catch (ReflectiveOperationException | IOException e) {
      fail(event.channel + ": does not decode: " + e);
    }
  }

  private void fail(String why) {
    if (failures++ < 10) System.err.println("SpyTypeCheck: " + why);
  }

  private void print(String path) throws ReflectiveOperationException {
    System.out.println("log: " + path);
    for (Map.Entry<String, Integer> e : counts.entrySet()) {
      System.out.println("  " + e.getKey() + ": " + e.getValue());
    }
    System.out.println("messages of no a3lcm type: " + failures);
    System.out.println("vehicle states: " + vehicleStates);
    printPosition("first", firstState);
    printPosition("last", lastState);
  }

  private static void printPosition(String which, Object state) throws ReflectiveOperationException {
    if (state == null) return;
    long utime_us = state.getClass().getField("utime_us").getLong(state);
    double[] p = (double[]) state.getClass().getField("p_W_m").get(state);
    System.out.println(String.format(java.util.Locale.ROOT, "%s position: t=%.3f s  p_W_m=(%.3f, %.3f, %.3f) m",
                                     which, utime_us / 1e6, p[0], p[1], p[2]));
  }
}
